#include "tsgraphs/sim/scene_mesh.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>
#include <unordered_set>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/core/voxel_key.hpp"
#include "tsgraphs/io/pcd.hpp"
#include "tsgraphs/scene/scene_geometry.hpp"

namespace tsgraphs::sim {
namespace {

double deg2rad(double d) { return d * M_PI / 180.0; }

void add_region(LabelledMesh* mesh, const std::vector<Polygon2>& include,
                const std::vector<Polygon2>& exclude, double z, PointLabel label) {
  for (const Triangle2& t : triangulate_region(include, exclude)) {
    mesh->add_triangle({t[0].x(), t[0].y(), z}, {t[1].x(), t[1].y(), z}, {t[2].x(), t[2].y(), z}, label);
  }
}

void add_wall(LabelledMesh* mesh, const scene::Wall& wall, double elevation) {
  const Vec2 dir = (wall.to - wall.from).normalized();
  const double yaw = std::atan2(dir.y(), dir.x());
  for (const scene::WallPiece& p : scene::wall_pieces(wall)) {
    const Vec2 c = wall.from + 0.5 * (p.s0 + p.s1) * dir;
    mesh->add_box(c, {0.5 * (p.s1 - p.s0), 0.5 * wall.thickness}, yaw, elevation + p.z0, elevation + p.z1,
                  PointLabel::kWall);
  }
  // A window's glass: one pane on the centre line, as a glass railing's (a ray meets it once).
  for (const scene::GlassPane& g : scene::glass_panes(wall)) {
    const Vec2 a2 = wall.from + g.s0 * dir, b2 = wall.from + g.s1 * dir;
    const Eigen::Vector3d a(a2.x(), a2.y(), elevation + g.z0), b(b2.x(), b2.y(), elevation + g.z0);
    const Eigen::Vector3d up(0.0, 0.0, g.z1 - g.z0);
    const float t = static_cast<float>(g.transmission);
    mesh->add_triangle(a, b, b + up, PointLabel::kWall, t);
    mesh->add_triangle(a, b + up, a + up, PointLabel::kWall, t);
  }
}

void add_railing(LabelledMesh* mesh, const scene::Railing& r, double elevation) {
  const Vec2 d = r.to - r.from;
  const double length = d.norm();
  const Vec2 dir = d / length;
  const double yaw = std::atan2(dir.y(), dir.x());
  const Vec2 mid = 0.5 * (r.from + r.to);
  if (r.style == scene::RailingStyle::kGlass) {
    // One pane, no thickness: a ray meets it once, and passes with the railing's transmission.
    const Eigen::Vector3d a(r.from.x(), r.from.y(), elevation), b(r.to.x(), r.to.y(), elevation);
    const Eigen::Vector3d up(0.0, 0.0, r.height);
    const float t = static_cast<float>(r.transmission);
    mesh->add_triangle(a, b, b + up, PointLabel::kRailing, t);
    mesh->add_triangle(a, b + up, a + up, PointLabel::kRailing, t);
    return;
  }
  if (r.style == scene::RailingStyle::kSolid) {
    mesh->add_box(mid, {0.5 * length, 0.5 * scene::RailingGeometry::kSolidThickness}, yaw, elevation,
                  elevation + r.height, PointLabel::kRailing);
    return;
  }
  const double top = elevation + r.height;
  const double rail_bottom = top - scene::RailingGeometry::kTopRailHeight;
  const double half_post = 0.5 * scene::RailingGeometry::kPostWidth;
  mesh->add_box(mid, {0.5 * length, half_post}, yaw, rail_bottom, top, PointLabel::kRailing);
  const int posts = static_cast<int>(std::floor(length / scene::RailingGeometry::kPostSpacing + 1e-9)) + 1;
  for (int k = 0; k < posts; ++k) {
    const double s = std::min(k * scene::RailingGeometry::kPostSpacing, length);
    mesh->add_box(r.from + s * dir, {half_post, half_post}, yaw, elevation, rail_bottom,
                  PointLabel::kRailing);
  }
  // A last post at the far end when the spacing does not land on it.
  if (length - (posts - 1) * scene::RailingGeometry::kPostSpacing > half_post * 2) {
    mesh->add_box(r.to, {half_post, half_post}, yaw, elevation, rail_bottom, PointLabel::kRailing);
  }
}

void add_ramp(LabelledMesh* mesh, const scene::Scene& scene, const scene::Ramp& ramp) {
  for (const Triangle2& t : triangulate_region({ramp.polygon})) {
    Eigen::Vector3d v[3];
    for (int i = 0; i < 3; ++i) v[i] = {t[i].x(), t[i].y(), scene::ramp_height(scene, ramp, t[i])};
    mesh->add_triangle(v[0], v[1], v[2], PointLabel::kRamp);
  }
}

/// Exact voxel indices (a packed key wraps far out); the shared key only hashes them.
struct IndexHash {
  std::size_t operator()(const Eigen::Vector3i& k) const { return KeyHash{}(voxel_key(k.x(), k.y(), k.z())); }
};
using VoxelSet = std::unordered_set<Eigen::Vector3i, IndexHash>;

/// The voxel map's cloud snapped to the voxel grid through its first point, so voxel centres
/// stay exact and a dense cloud becomes one cube per occupied voxel.
struct Voxels {
  Eigen::Vector3d origin;
  VoxelSet occupied;
  std::vector<Eigen::Vector3i> keys;  ///< the occupied voxels, in the order of their first point
};

Voxels snap_to_voxels(const PointCloud& cloud, double s) {
  Voxels voxels;
  voxels.origin = cloud.points.front().cast<double>();
  for (const Eigen::Vector3f& p : cloud.points) {
    const Eigen::Vector3i k = ((p.cast<double>() - voxels.origin) / s).array().round().cast<int>();
    if (voxels.occupied.insert(k).second) voxels.keys.push_back(k);
  }
  return voxels;
}

/// Where the voxel map stands in the scene, and what its voxels are.
class VoxelPlacement {
 public:
  VoxelPlacement(const scene::VoxelMap& vm, const scene::Level& level, const Eigen::Vector3d& origin)
      : vm_(vm),
        level_(level),
        origin_(origin),
        c_(std::cos(deg2rad(vm.yaw_deg))),
        sn_(std::sin(deg2rad(vm.yaw_deg))) {}

  Eigen::Vector3d to_world(const Eigen::Vector3d& p) const {
    return Eigen::Vector3d(c_ * p.x() - sn_ * p.y() + vm_.offset.x(),
                           sn_ * p.x() + c_ * p.y() + vm_.offset.y(),
                           p.z() + vm_.offset.z() + level_.elevation);
  }

  /// The map's label, or with kAuto floor and ceiling by height and wall between.
  PointLabel label_of(const Eigen::Vector3i& k) const {
    const double s = vm_.voxel_size;
    const double z_rel = origin_.z() + s * k.z() + vm_.offset.z();
    switch (vm_.label) {
      case scene::VoxelLabel::kWall:
        return PointLabel::kWall;
      case scene::VoxelLabel::kBox:
        return PointLabel::kBox;
      case scene::VoxelLabel::kRailing:
        return PointLabel::kRailing;
      case scene::VoxelLabel::kAuto:
        break;
    }
    return std::abs(z_rel) <= s                    ? PointLabel::kFloor
           : std::abs(z_rel - level_.ceiling) <= s ? PointLabel::kCeiling
                                                   : PointLabel::kWall;
  }

 private:
  const scene::VoxelMap& vm_;
  const scene::Level& level_;
  Eigen::Vector3d origin_;
  double c_, sn_;
};

/// A voxel's side face towards an empty neighbour (direction dir of side_directions()).
struct SideFace {
  int dir, x, y;
  std::uint32_t label;
  int z;
  bool operator<(const SideFace& o) const {
    return std::tie(dir, x, y, label, z) < std::tie(o.dir, o.x, o.y, o.label, o.z);
  }
};

const Eigen::Vector3i* side_directions() {
  static const Eigen::Vector3i kSides[4] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}};
  return kSides;
}

/// Adds the top and bottom faces between an occupied voxel and an empty one to `mesh`, and
/// returns the side faces, to be merged per column.
std::vector<SideFace> add_top_bottom_faces(LabelledMesh* mesh, const Voxels& voxels, double s,
                                           const VoxelPlacement& place) {
  static const Eigen::Vector3i kUpDown[2] = {{0, 0, 1}, {0, 0, -1}};
  const Eigen::Vector3i* sides_dir = side_directions();
  std::vector<SideFace> sides;
  for (const Eigen::Vector3i& k : voxels.keys) {
    const PointLabel label = place.label_of(k);
    for (int d = 0; d < 4; ++d) {
      if (!voxels.occupied.count(k + sides_dir[d]))
        sides.push_back({d, k.x(), k.y(), static_cast<std::uint32_t>(label), k.z()});
    }
    for (const Eigen::Vector3i& n : kUpDown) {
      if (voxels.occupied.count(k + n)) continue;
      const Eigen::Vector3d fc = voxels.origin + s * k.cast<double>() + 0.5 * s * n.cast<double>();
      const Eigen::Vector3d u = 0.5 * s * Eigen::Vector3d::UnitX(), v = 0.5 * s * Eigen::Vector3d::UnitY();
      mesh->add_triangle(place.to_world(fc - u - v), place.to_world(fc + u - v), place.to_world(fc + u + v),
                         label);
      mesh->add_triangle(place.to_world(fc - u - v), place.to_world(fc + u + v), place.to_world(fc - u + v),
                         label);
    }
  }
  return sides;
}

/// Adds the side faces merged into one tall quad per run of the same label up a column: a
/// wall extruded from an occupancy map is then a few triangles per cell, not a few per voxel.
void add_side_faces(LabelledMesh* mesh, std::vector<SideFace> sides, const Eigen::Vector3d& origin, double s,
                    const VoxelPlacement& place) {
  std::sort(sides.begin(), sides.end());
  for (std::size_t i = 0; i < sides.size();) {
    std::size_t j = i + 1;
    while (j < sides.size() && sides[j].dir == sides[i].dir && sides[j].x == sides[i].x &&
           sides[j].y == sides[i].y && sides[j].label == sides[i].label && sides[j].z == sides[j - 1].z + 1)
      ++j;
    const SideFace& f = sides[i];
    const Eigen::Vector3d n = side_directions()[f.dir].cast<double>();
    const Eigen::Vector3d base = origin + s * Eigen::Vector3d(f.x, f.y, 0.0) + 0.5 * s * n;
    const Eigen::Vector3d u = 0.5 * s * (f.dir < 2 ? Eigen::Vector3d::UnitY() : Eigen::Vector3d::UnitX());
    const Eigen::Vector3d z0 = Eigen::Vector3d(0, 0, origin.z() + s * (f.z - 0.5) - base.z());
    const Eigen::Vector3d z1 = Eigen::Vector3d(0, 0, origin.z() + s * (sides[j - 1].z + 0.5) - base.z());
    const auto label = static_cast<PointLabel>(f.label);
    mesh->add_triangle(place.to_world(base - u + z0), place.to_world(base + u + z0),
                       place.to_world(base + u + z1), label);
    mesh->add_triangle(place.to_world(base - u + z0), place.to_world(base + u + z1),
                       place.to_world(base - u + z1), label);
    i = j;
  }
}

/// The faces between an occupied voxel and an empty one: the visible surface.
void add_voxel_map(LabelledMesh* mesh, const scene::Scene& scene, const scene::VoxelMap& vm) {
  const PointCloud cloud = io::read_pcd(vm.file);
  if (cloud.empty()) throw InputError(vm.file + ": voxel map has no finite points");
  const double s = vm.voxel_size;
  const Voxels voxels = snap_to_voxels(cloud, s);
  const VoxelPlacement place(vm, scene.levels[vm.level], voxels.origin);
  add_side_faces(mesh, add_top_bottom_faces(mesh, voxels, s, place), voxels.origin, s, place);
}

}  // namespace

void LabelledMesh::add_triangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                                PointLabel label, float transmission_) {
  const int base = static_cast<int>(vertices.size());
  vertices.push_back(a.cast<float>());
  vertices.push_back(b.cast<float>());
  vertices.push_back(c.cast<float>());
  triangles.emplace_back(base, base + 1, base + 2);
  labels.push_back(static_cast<std::uint32_t>(label));
  transmission.push_back(transmission_);
}

void LabelledMesh::add_box(const Eigen::Vector2d& center, const Eigen::Vector2d& half_size, double yaw,
                           double z0, double z1, PointLabel label, float transmission_) {
  const Vec2 ax(std::cos(yaw), std::sin(yaw));
  const Vec2 ay(-ax.y(), ax.x());
  const Vec2 corners2[4] = {
      center - half_size.x() * ax - half_size.y() * ay, center + half_size.x() * ax - half_size.y() * ay,
      center + half_size.x() * ax + half_size.y() * ay, center - half_size.x() * ax + half_size.y() * ay};
  const int base = static_cast<int>(vertices.size());
  for (double z : {z0, z1}) {
    for (const Vec2& p : corners2)
      vertices.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(z));
  }
  static const int kFaces[6][4] = {{0, 1, 2, 3}, {4, 7, 6, 5}, {0, 4, 5, 1},
                                   {1, 5, 6, 2}, {2, 6, 7, 3}, {3, 7, 4, 0}};
  for (const auto& f : kFaces) {
    triangles.emplace_back(base + f[0], base + f[1], base + f[2]);
    triangles.emplace_back(base + f[0], base + f[2], base + f[3]);
    labels.push_back(static_cast<std::uint32_t>(label));
    labels.push_back(static_cast<std::uint32_t>(label));
    transmission.push_back(transmission_);
    transmission.push_back(transmission_);
  }
}

// The slab between two storeys has a thickness (from the lower ceiling up to the upper
// floor); inside a void its edge is a vertical face. Labelled wall: vertical structure, not
// walkable ground.
static void add_void_edges(LabelledMesh* mesh, const scene::Scene& scene, int level) {
  const scene::Level& l = scene.levels[level];
  double below_ceiling = -std::numeric_limits<double>::infinity();
  for (const scene::Level& other : scene.levels) {
    if (other.elevation < l.elevation)
      below_ceiling = std::max(below_ceiling, other.elevation + other.ceiling);
  }
  if (!(below_ceiling < l.elevation)) return;  // no storey below, or no slab thickness
  for (const Polygon2& v : l.voids) {
    for (std::size_t i = 0, n = v.size(); i < n; ++i) {
      const Vec2& a = v[i];
      const Vec2& b = v[(i + 1) % n];
      const Eigen::Vector3d a0(a.x(), a.y(), below_ceiling), b0(b.x(), b.y(), below_ceiling);
      const Eigen::Vector3d a1(a.x(), a.y(), l.elevation), b1(b.x(), b.y(), l.elevation);
      mesh->add_triangle(a0, b0, b1, PointLabel::kWall);
      mesh->add_triangle(a0, b1, a1, PointLabel::kWall);
    }
  }
}

LabelledMesh build_scene_mesh(const scene::Scene& scene) {
  LabelledMesh mesh;
  for (std::size_t i = 0; i < scene.levels.size(); ++i) {
    const scene::Level& l = scene.levels[i];
    add_region(&mesh, {l.slab}, l.voids, l.elevation, PointLabel::kFloor);
    add_region(&mesh, {l.slab}, scene::ceiling_holes(scene, static_cast<int>(i)), l.elevation + l.ceiling,
               PointLabel::kCeiling);
    add_void_edges(&mesh, scene, static_cast<int>(i));
  }
  for (const scene::Wall& w : scene.walls) add_wall(&mesh, w, scene.levels[w.level].elevation);
  for (const scene::Railing& r : scene.railings) add_railing(&mesh, r, scene.levels[r.level].elevation);
  for (const scene::Box& b : scene.boxes) {
    const double e = scene.levels[b.level].elevation;
    const Vec2 c = 0.5 * (b.min.head<2>() + b.max.head<2>());
    const Vec2 half = 0.5 * (b.max.head<2>() - b.min.head<2>());
    mesh.add_box(c, half, deg2rad(b.yaw_deg), e + b.min.z(), e + b.max.z(), PointLabel::kBox);
  }
  for (const scene::Ramp& r : scene.ramps) add_ramp(&mesh, scene, r);
  for (const scene::VoxelMap& v : scene.voxel_maps) add_voxel_map(&mesh, scene, v);
  return mesh;
}

}  // namespace tsgraphs::sim
