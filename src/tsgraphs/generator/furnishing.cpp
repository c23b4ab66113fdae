#include "tsgraphs/generator/furnishing.hpp"

#include <algorithm>
#include <cmath>

#include "tsgraphs/core/rect.hpp"

namespace tsgraphs::generator {
namespace {

constexpr double kDoorKeepOut = 1.3;        // m round a door's centre kept free (its approach, both sides)
constexpr double kItemGap = 0.5;            // m between two pieces of furniture
constexpr double kWallGap = 0.03;           // m between a piece and the wall it stands against
constexpr double kFreeStandingGap = 1.0;    // m between free-standing furniture and the walls
constexpr int kOfficeItemsMax = 3;          // per room
constexpr double kOfficeItemChance = 0.45;  // per wall long enough
constexpr double kSmallRoomArea = 8.0;      // m^2: such a room gets one piece at most

struct Item {
  const char* label;
  double length_lo, length_hi, depth_lo, depth_hi, height_lo, height_hi;
};
// Office furniture against a wall: desks, shelves (a tall shelf is a plane to the room layer,
// not a wall of the ground truth) and cabinets.
constexpr Item kOfficeItems[] = {
    {"desk", 1.2, 2.0, 0.6, 0.8, 0.72, 0.76},
    {"shelf", 0.8, 3.0, 0.35, 0.45, 1.6, 2.2},
    {"cabinet", 0.8, 1.6, 0.45, 0.6, 0.9, 1.3},
};

class Placer {
 public:
  Placer(const scene::Scene& scene, int level, const Polygon2& face,
         const std::vector<OrientedRect>& keep_clear)
      : face_(face), doors_(door_approaches(scene, level)), placed_(keep_clear) {}

  /// True (and the footprint kept) when `r` lies inside the face, clear of the doors'
  /// approaches and of every piece placed before (by `gap`).
  bool try_place(const OrientedRect& r, double gap = kItemGap) {
    const Polygon2 corners = r.corners();
    for (const Vec2& p : corners) {
      if (!contains(face_, p)) return false;
    }
    if (!contains(face_, r.center)) return false;
    for (const DoorApproach& d : doors_) {
      if (distance(r, d.center) < d.radius) return false;
    }
    OrientedRect grown = r;
    grown.size += Vec2::Constant(2 * gap);
    for (const OrientedRect& o : placed_) {
      if (intersection_area(grown, o) > 1e-9) return false;
    }
    placed_.push_back(r);
    return true;
  }
  /// Distance from the footprint to the face's edges (how free-standing it is).
  double distance_to_walls(const OrientedRect& r) const {
    double d = 1e18;
    for (const Vec2& p : r.corners()) {
      for (std::size_t i = 0; i < face_.size(); ++i)
        d = std::min(d, distance_to_segment(p, face_[i], face_[(i + 1) % face_.size()]));
    }
    return d;
  }

 private:
  Polygon2 face_;
  std::vector<DoorApproach> doors_;
  std::vector<OrientedRect> placed_;
};

scene::Box box_of(const OrientedRect& r, double z0, double z1, int level, const char* label) {
  scene::Box b;
  b.level = level;
  b.min = Eigen::Vector3d(r.center.x() - 0.5 * r.size.x(), r.center.y() - 0.5 * r.size.y(), z0);
  b.max = Eigen::Vector3d(r.center.x() + 0.5 * r.size.x(), r.center.y() + 0.5 * r.size.y(), z1);
  b.yaw_deg = r.yaw * 180.0 / M_PI;
  b.label = label;
  return b;
}

void furnish_office(const Polygon2& face, int level, Rng& rng, scene::Scene* scene,
                    const std::vector<OrientedRect>& keep_clear) {
  Placer placer(*scene, level, face, keep_clear);
  const int max_items = area(face) < kSmallRoomArea ? 1 : kOfficeItemsMax;
  int placed = 0;
  const double orient = signed_area(face) >= 0 ? 1.0 : -1.0;
  for (std::size_t i = 0; i < face.size() && placed < max_items; ++i) {
    const Vec2 a = face[i], b = face[(i + 1) % face.size()];
    const double len = (b - a).norm();
    const Item& item = kOfficeItems[rng.integer(0, 2)];
    if (!rng.chance(kOfficeItemChance) || len < item.length_lo + 0.4) continue;
    const double l = std::min(rng.uniform(item.length_lo, item.length_hi), len - 0.4);
    const double d = rng.uniform(item.depth_lo, item.depth_hi);
    const Vec2 u = (b - a) / len, inward = orient * Vec2(-u.y(), u.x());
    const double s = rng.uniform(0.2 + 0.5 * l, len - 0.2 - 0.5 * l);
    OrientedRect r;
    r.center = a + s * u + (kWallGap + 0.5 * d) * inward;
    r.size = Vec2(l, d);
    r.yaw = std::atan2(u.y(), u.x());
    if (!placer.try_place(r)) continue;
    scene->boxes.push_back(box_of(r, 0.0, rng.uniform(item.height_lo, item.height_hi), level, item.label));
    ++placed;
  }
}

void bounds(const Polygon2& face, Vec2* lo, Vec2* hi) {
  *lo = *hi = face.front();
  for (const Vec2& p : face) {
    *lo = lo->cwiseMin(p);
    *hi = hi->cwiseMax(p);
  }
}

void furnish_shelves(const Polygon2& face, int level, Rng& rng, scene::Scene* scene,
                     const std::vector<OrientedRect>& keep_clear) {
  Placer placer(*scene, level, face, keep_clear);
  Vec2 lo, hi;
  bounds(face, &lo, &hi);
  const bool rows_along_x = rng.chance(0.5);
  const double depth = rng.uniform(0.4, 0.6), aisle = rng.uniform(1.0, 1.8), height = rng.uniform(1.8, 2.2);
  const double cross = rng.uniform(1.2, 1.6);  // gaps cutting the rows
  const double run_lo = 2.0, run_hi = rng.uniform(3.0, 6.0);
  // Rows across the hall, kFreeStandingGap off the walls, a row every depth + aisle.
  const double a0 = (rows_along_x ? lo.y() : lo.x()) + kFreeStandingGap + rng.uniform(0.5, 1.5);
  const double a1 = (rows_along_x ? hi.y() : hi.x()) - kFreeStandingGap;
  const double b0 = (rows_along_x ? lo.x() : lo.y()) + kFreeStandingGap + rng.uniform(0.5, 1.5);
  const double b1 = (rows_along_x ? hi.x() : hi.y()) - kFreeStandingGap;
  for (double a = a0; a + depth <= a1; a += depth + aisle) {
    for (double b = b0; b + run_lo <= b1;) {
      const double len = std::min(rng.uniform(run_lo, run_hi), b1 - b);
      OrientedRect r;
      r.center = rows_along_x ? Vec2(b + 0.5 * len, a + 0.5 * depth) : Vec2(a + 0.5 * depth, b + 0.5 * len);
      r.size = rows_along_x ? Vec2(len, depth) : Vec2(depth, len);
      r.yaw = 0.0;
      if (placer.try_place(r, 0.0) && placer.distance_to_walls(r) >= kFreeStandingGap)
        scene->boxes.push_back(box_of(r, 0.0, height, level, "bookshelf"));
      b += len + cross;
    }
  }
}

void furnish_open_plan(const Polygon2& face, int level, double ceiling, Rng& rng, scene::Scene* scene,
                       const std::vector<OrientedRect>& keep_clear) {
  Placer placer(*scene, level, face, keep_clear);
  Vec2 lo, hi;
  bounds(face, &lo, &hi);
  // Pillars on a grid, floor to ceiling.
  const double spacing = rng.uniform(6.0, 9.0), side = rng.uniform(0.4, 0.6);
  for (double x = lo.x() + spacing; x < hi.x() - 0.5 * spacing; x += spacing) {
    for (double y = lo.y() + spacing; y < hi.y() - 0.5 * spacing; y += spacing) {
      OrientedRect r;
      r.center = Vec2(x, y);
      r.size = Vec2(side, side);
      if (placer.try_place(r, 0.8)) scene->boxes.push_back(box_of(r, 0.0, ceiling, level, "pillar"));
    }
  }
  // Desk clusters: two rows of desks back to back with a partition between, lower than the ceiling.
  const double desk_w = rng.uniform(1.4, 1.8), desk_d = rng.uniform(0.7, 0.8);
  const double partition_h = rng.uniform(1.2, 1.7);
  const int per_row = rng.integer(2, 4);
  const double cluster_w = per_row * desk_w, cluster_d = 2 * desk_d + 0.05;
  const double step_x = cluster_w + rng.uniform(1.6, 2.6), step_y = cluster_d + rng.uniform(1.8, 2.8);
  for (double y = lo.y() + 1.5; y + cluster_d < hi.y() - 1.5; y += step_y) {
    for (double x = lo.x() + 1.5; x + cluster_w < hi.x() - 1.5; x += step_x) {
      if (rng.chance(0.25)) continue;  // an open space in the layout
      OrientedRect r;
      r.center = Vec2(x + 0.5 * cluster_w, y + 0.5 * cluster_d);
      r.size = Vec2(cluster_w, cluster_d);
      if (!placer.try_place(r, 1.0) || placer.distance_to_walls(r) < 1.2) continue;
      for (int row = 0; row < 2; ++row) {
        OrientedRect desk;
        desk.center = Vec2(r.center.x(), y + 0.5 * desk_d + row * (desk_d + 0.05));
        desk.size = Vec2(cluster_w, desk_d);
        scene->boxes.push_back(box_of(desk, 0.0, 0.74, level, "desk"));
      }
      scene::Wall partition;
      partition.level = level;
      partition.from = Vec2(x, y + desk_d + 0.025);
      partition.to = Vec2(x + cluster_w, y + desk_d + 0.025);
      partition.thickness = 0.05;
      partition.height = partition_h;
      scene->walls.push_back(partition);
    }
  }
}

void furnish_lobby(const Polygon2& face, int level, double ceiling, Rng& rng, scene::Scene* scene,
                   const std::vector<OrientedRect>& keep_clear) {
  Placer placer(*scene, level, face, keep_clear);
  Vec2 lo, hi;
  bounds(face, &lo, &hi);
  const double spacing = rng.uniform(7.0, 10.0);
  for (double x = lo.x() + spacing; x < hi.x() - 0.5 * spacing; x += spacing) {
    for (double y = lo.y() + spacing; y < hi.y() - 0.5 * spacing; y += spacing) {
      OrientedRect r;
      r.center = Vec2(x, y);
      r.size = Vec2::Constant(0.5);
      if (placer.try_place(r, 1.0)) scene->boxes.push_back(box_of(r, 0.0, ceiling, level, "pillar"));
    }
  }
  for (int k = 0; k < 4; ++k) {
    OrientedRect r;
    // One draw per statement (a call's argument order is unspecified): y first, as gcc drew it.
    const double cy = rng.uniform(lo.y() + 2, hi.y() - 2);
    const double cx = rng.uniform(lo.x() + 2, hi.x() - 2);
    r.center = Vec2(cx, cy);
    r.size = Vec2(rng.uniform(1.5, 3.0), 0.5);
    r.yaw = rng.chance(0.5) ? 0.0 : M_PI_2;
    if (placer.try_place(r, 1.0)) scene->boxes.push_back(box_of(r, 0.0, 0.45, level, "bench"));
  }
}

}  // namespace

std::vector<DoorApproach> door_approaches(const scene::Scene& scene, int level) {
  std::vector<DoorApproach> out;
  for (const scene::Wall& w : scene.walls) {
    if (w.level != level) continue;
    const Vec2 dir = (w.to - w.from).normalized();
    for (const scene::Opening& o : w.openings) {
      if (o.sill <= 0.0) out.push_back({w.from + o.at * dir, std::max(kDoorKeepOut, 0.5 * o.width + 0.8)});
    }
  }
  return out;
}

void furnish(const FloorPlan& plan, const PlanResult& result, int level, Rng& rng, scene::Scene* scene,
             const std::vector<OrientedRect>& keep_clear) {
  const double ceiling = scene->levels.at(level).ceiling;
  for (std::size_t s = 0; s < plan.spaces.size(); ++s) {
    const Polygon2& face = result.faces[s];
    switch (plan.spaces[s].furnishing) {
      case Furnishing::kNone:
        break;
      case Furnishing::kOffice:
        furnish_office(face, level, rng, scene, keep_clear);
        break;
      case Furnishing::kShelves:
        furnish_shelves(face, level, rng, scene, keep_clear);
        break;
      case Furnishing::kOpenPlan:
        furnish_open_plan(face, level, ceiling, rng, scene, keep_clear);
        break;
      case Furnishing::kLobby:
        furnish_lobby(face, level, ceiling, rng, scene, keep_clear);
        break;
    }
  }
}

}  // namespace tsgraphs::generator
