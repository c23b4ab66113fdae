#include "tsgraphs/eval/wall_metrics.hpp"

#include <algorithm>
#include <cmath>

namespace tsgraphs::eval {
namespace {

Eigen::Vector2d perp(const Eigen::Vector2d& u) { return {-u.y(), u.x()}; }

// Overlap length of the projections of segments [a0,b0] and [a1,b1] on direction u.
double overlap_along(const Eigen::Vector2d& u, const Eigen::Vector2d& a0, const Eigen::Vector2d& b0,
                     const Eigen::Vector2d& a1, const Eigen::Vector2d& b1) {
  const double s0 = std::min(u.dot(a0), u.dot(b0)), e0 = std::max(u.dot(a0), u.dot(b0));
  const double s1 = std::min(u.dot(a1), u.dot(b1)), e1 = std::max(u.dot(a1), u.dot(b1));
  return std::min(e0, e1) - std::max(s0, s1);
}

}  // namespace

std::vector<WallFaceTruth> wall_faces(const scene::Scene& scene) {
  // Pieces shorter than this (m) between two junctions are not faces anyone would map.
  constexpr double kMinPiece = 0.3;
  std::vector<WallFaceTruth> faces;
  for (std::size_t i = 0; i < scene.walls.size(); ++i) {
    const scene::Wall& w = scene.walls[i];
    const Eigen::Vector2d d = w.to - w.from;
    if (d.norm() <= 0.0) continue;
    const Eigen::Vector2d u = d.normalized(), n = perp(u);
    const double start = w.joined_from ? -0.5 * w.thickness : 0.0;
    const double end = d.norm() + (w.joined_to ? 0.5 * w.thickness : 0.0);
    const double z0 = scene.levels[w.level].elevation;
    for (const int side : {1, -1}) {
      // Walls that end on this side of w split its face: one face per stretch between them.
      std::vector<std::pair<double, double>> cuts;  // [s0, s1] along w taken by another wall
      for (std::size_t j = 0; j < scene.walls.size(); ++j) {
        const scene::Wall& x = scene.walls[j];
        if (j == i || x.level != w.level) continue;
        for (const auto& [e, other] : {std::pair{x.from, x.to}, std::pair{x.to, x.from}}) {
          const double across = n.dot(e - w.from), along = u.dot(e - w.from);
          if (std::abs(across) > 0.5 * (w.thickness + x.thickness) + 1e-6) continue;
          if (side * n.dot(other - e) <= 0.0 || along < start || along > end) continue;
          cuts.emplace_back(along - 0.5 * x.thickness, along + 0.5 * x.thickness);
        }
      }
      std::sort(cuts.begin(), cuts.end());
      std::vector<std::pair<double, double>> pieces;
      double s = start;
      for (const auto& [c0, c1] : cuts) {
        if (c0 > s) pieces.emplace_back(s, c0);
        s = std::max(s, c1);
      }
      if (end > s) pieces.emplace_back(s, end);
      for (const auto& [s0, s1] : pieces) {
        if (s1 - s0 < kMinPiece) continue;
        WallFaceTruth f;
        f.wall = static_cast<int>(i);
        f.side = side;
        const Eigen::Vector2d offset = side * 0.5 * w.thickness * n;
        f.a = w.from + s0 * u + offset;
        f.b = w.from + s1 * u + offset;
        f.z0 = z0;
        f.z1 = z0 + w.height;
        f.plane = Plane::from_point_normal(Eigen::Vector3d(f.a.x(), f.a.y(), z0),
                                           Eigen::Vector3d(side * n.x(), side * n.y(), 0.0));
        faces.push_back(f);
      }
    }
  }
  return faces;
}

void count_face_hits(const std::vector<WallFaceTruth>& faces, const PointCloud& scan,
                     const Pose3& T_world_sensor, const WallMetricsConfig& config,
                     std::vector<FaceHits>* hits) {
  hits->resize(faces.size());
  if (!scan.has_labels()) return;
  const double max2 = config.max_range * config.max_range;
  for (std::size_t i = 0; i < scan.size(); ++i) {
    if (scan.labels[i] != static_cast<std::uint32_t>(PointLabel::kWall)) continue;
    const Eigen::Vector3d p_s = scan.points[i].cast<double>();
    if (!p_s.allFinite() || p_s.squaredNorm() > max2) continue;
    const Eigen::Vector3d p = T_world_sensor * p_s;
    for (std::size_t f = 0; f < faces.size(); ++f) {
      const WallFaceTruth& face = faces[f];
      // On the face's front side (the side the sensor can see), within its rectangle.
      if (std::abs(face.plane.signed_distance(p)) > config.attribution_distance) continue;
      if (face.plane.signed_distance(T_world_sensor.translation()) <= 0.0) continue;
      if (p.z() < face.z0 - config.attribution_distance || p.z() > face.z1 + config.attribution_distance)
        continue;
      const Eigen::Vector2d u = (face.b - face.a).normalized();
      const double s = u.dot(p.head<2>() - face.a);
      if (s < -config.attribution_distance || s > (face.b - face.a).norm() + config.attribution_distance)
        continue;
      (*hits)[f].count += 1;
      (*hits)[f].sum += p;
      break;
    }
  }
}

WallErrors wall_errors(const std::vector<WallFaceTruth>& faces, const std::vector<FaceHits>& hits,
                       const std::vector<MappedWall>& mapped, const Pose3& T_world_map,
                       const WallMetricsConfig& config) {
  // Mapped planes in the world frame.
  std::vector<MappedWall> world;
  for (const MappedWall& m : mapped) {
    MappedWall w = m;
    w.plane = m.plane.transformed(T_world_map);
    const Eigen::Vector3d a = T_world_map * Eigen::Vector3d(m.a.x(), m.a.y(), 0.0);
    const Eigen::Vector3d b = T_world_map * Eigen::Vector3d(m.b.x(), m.b.y(), 0.0);
    w.a = a.head<2>();
    w.b = b.head<2>();
    w.z0 = m.z0 + T_world_map.translation().z();  // the alignment is a yaw and a shift in practice
    w.z1 = m.z1 + T_world_map.translation().z();
    world.push_back(w);
  }
  const double cos_match = std::cos(config.match_angle_deg * M_PI / 180.0);
  WallErrors e;
  double sum_dist = 0.0, sum_angle = 0.0;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    if (f >= hits.size() || hits[f].count < config.min_points) continue;
    ++e.n_faces_seen;
    const WallFaceTruth& face = faces[f];
    const Eigen::Vector3d centre = hits[f].sum / hits[f].count;
    const Eigen::Vector2d u = (face.b - face.a).normalized();
    std::vector<std::size_t> matches;
    for (std::size_t m = 0; m < world.size(); ++m) {
      const MappedWall& w = world[m];
      if (w.plane.n.dot(face.plane.n) < cos_match) continue;
      if (std::abs(w.plane.signed_distance(centre)) > config.match_distance) continue;
      if (overlap_along(u, face.a, face.b, w.a, w.b) < config.min_overlap) continue;
      if (std::min(face.z1, w.z1) - std::max(face.z0, w.z0) < config.min_overlap) continue;  // another storey
      matches.push_back(m);
    }
    if (matches.empty()) continue;
    ++e.n_faces_mapped;
    // The associated plane is the closest at the seen centre; the others, where they cover
    // the same stretch of the face as it, are duplicates.
    const auto err_of = [&](std::size_t m) { return std::abs(world[m].plane.signed_distance(centre)); };
    const std::size_t best = *std::min_element(
        matches.begin(), matches.end(), [&](std::size_t x, std::size_t y) { return err_of(x) < err_of(y); });
    const double dist = err_of(best);
    const double angle =
        std::acos(std::clamp(world[best].plane.n.dot(face.plane.n), -1.0, 1.0)) * 180.0 / M_PI;
    sum_dist += dist;
    sum_angle += angle;
    e.max_dist_err = std::max(e.max_dist_err, dist);
    e.max_angle_err_deg = std::max(e.max_angle_err_deg, angle);
    for (std::size_t m : matches)
      if (m != best &&
          overlap_along(u, world[best].a, world[best].b, world[m].a, world[m].b) >= config.min_overlap)
        ++e.n_duplicates;
  }
  if (e.n_faces_mapped > 0) {
    e.mean_dist_err = sum_dist / e.n_faces_mapped;
    e.mean_angle_err_deg = sum_angle / e.n_faces_mapped;
  }
  return e;
}

}  // namespace tsgraphs::eval
