// Plane extraction on simulated scans, against the scene's true faces: every clearly visible
// wall face near the sensor is found once, with small normal and offset errors and its normal
// towards the sensor; floor and ceiling come out horizontal; a gap wider than the clustering
// tolerance splits one plane into two faces; degenerate input gives nothing, never NaN.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <limits>
#include <string>
#include <unordered_map>
#include <vector>

#include "tsgraphs/pipeline/prefilter.hpp"
#include "tsgraphs/core/polygon.hpp"
#include "tsgraphs/io/pcd.hpp"
#include "tsgraphs/scene/builtin_scenes.hpp"
#include "tsgraphs/scene/scene_loader.hpp"
#include "tsgraphs/sim/simulator.hpp"
#include "tsgraphs/walls/plane_extraction.hpp"

using namespace tsgraphs;
using walls::PlaneExtractionConfig;
using walls::PlaneObservation;

namespace {

constexpr double kDeg = M_PI / 180.0;
constexpr double kPrefilterVoxel = 0.1;  // the pipeline's default prefilter voxel (m)
constexpr double kNearRange = 8.0;       // wall faces this close to the sensor must be found (m)
constexpr double kOnFace = 0.05;         // a point this close to a true face lies on it (m)
constexpr double kMatchAngleDeg = 10.0;  // an observation belongs to a true face within this...
constexpr double kMatchOffset = 0.1;     // ...and this (m)
constexpr double kMaxAngleErrDeg = 0.5;  // wall faces...
constexpr double kAngleRefExtent =
    1.0;  // ...at least this long (m); a shorter face may tilt as far as puts its
          // ends as far off the true face (a fit's tilt grows as 1 / its extent)
constexpr double kMaxOffsetErr = 0.02;  // at the observation's centroid (m)
constexpr std::uint32_t kWall = static_cast<std::uint32_t>(PointLabel::kWall);

// The pipeline's own prefilter (NaN drop, range crop, one centroid per voxel).
PointCloud voxel_filter(const PointCloud& in, double voxel) {
  pipeline::PrefilterConfig config;
  config.voxel_size = voxel;
  return pipeline::prefilter(in, config);
}

// One vertical face of the scene in the world frame (a side of a wall, box, railing or void
// edge): its plane, normal out of the solid, and the rectangle it covers.
struct TrueFace {
  Plane plane;
  Eigen::Vector2d origin, along;  // 2-D start and unit direction of the face
  double s0 = 0.0, s1 = 0.0;      // extent along `along`
  double z0 = 0.0, z1 = 0.0;      // extent in height
  std::uint32_t label = 0;
  std::vector<Eigen::Vector4d> openings;  // s0, s1, z0, z1 of each door or window
  double s_of(const Eigen::Vector3d& p) const { return along.dot(p.head<2>() - origin); }
  bool contains(const Eigen::Vector3d& p, double margin) const {
    const double s = s_of(p);
    return std::abs(plane.signed_distance(p)) <= margin && s >= s0 - margin && s <= s1 + margin &&
           p.z() >= z0 - margin && p.z() <= z1 + margin;
  }
  double horizontal_distance(const Eigen::Vector3d& x) const {
    const double s = std::clamp(s_of(x), s0, s1);
    return (origin + s * along - x.head<2>()).norm();
  }
};

// A horizontal surface: floor, ceiling or box top, facing up (+1) or down (-1).
struct TrueLevelSurface {
  double z = 0.0;
  double facing = 1.0;
};

struct Truth {
  std::vector<TrueFace> faces;
  std::vector<TrueLevelSurface> surfaces;
};

TrueFace make_face(const Eigen::Vector2d& a, const Eigen::Vector2d& dir, double s0, double s1,
                   const Eigen::Vector2d& outward, double z0, double z1, PointLabel label) {
  TrueFace f;
  f.origin = a;
  f.along = dir;
  f.s0 = s0;
  f.s1 = s1;
  f.z0 = z0;
  f.z1 = z1;
  f.label = static_cast<std::uint32_t>(label);
  f.plane = Plane::from_point_normal(Eigen::Vector3d(a.x(), a.y(), z0),
                                     Eigen::Vector3d(outward.x(), outward.y(), 0.0));
  return f;
}

// Both sides of a slab of `thickness` along the segment a-b.
void add_slab_faces(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double thickness, double s0_extra,
                    double s1_extra, double z0, double z1, PointLabel label, std::vector<TrueFace>* faces) {
  const Eigen::Vector2d dir = (b - a).normalized();
  const Eigen::Vector2d side(-dir.y(), dir.x());
  for (const double sign : {1.0, -1.0}) {
    faces->push_back(make_face(a + sign * 0.5 * thickness * side, dir, -s0_extra, (b - a).norm() + s1_extra,
                               sign * side, z0, z1, label));
  }
}

Truth truth_of(const scene::Scene& scene) {
  Truth t;
  for (const scene::Wall& w : scene.walls) {
    const double z0 = scene.levels[w.level].elevation;
    add_slab_faces(w.from, w.to, w.thickness, w.joined_from ? 0.5 * w.thickness : 0.0,
                   w.joined_to ? 0.5 * w.thickness : 0.0, z0, z0 + w.height, PointLabel::kWall, &t.faces);
    for (std::size_t i = t.faces.size() - 2; i < t.faces.size(); ++i) {
      for (const scene::Opening& o : w.openings) {
        t.faces[i].openings.emplace_back(o.at - 0.5 * o.width, o.at + 0.5 * o.width, z0 + o.sill,
                                         z0 + o.sill + o.height);
      }
    }
  }
  for (const scene::Railing& r : scene.railings) {
    const double z0 = scene.levels[r.level].elevation;
    const double thickness = r.style == scene::RailingStyle::kSolid ? scene::RailingGeometry::kSolidThickness
                                                                    : scene::RailingGeometry::kPostWidth;
    add_slab_faces(r.from, r.to, thickness, 0.0, 0.0, z0, z0 + r.height, PointLabel::kRailing, &t.faces);
  }
  for (const scene::Box& b : scene.boxes) {
    const double z0 = scene.levels[b.level].elevation;
    const Eigen::Vector2d centre = 0.5 * (b.min + b.max).head<2>();
    const Eigen::Vector2d half = 0.5 * (b.max - b.min).head<2>();
    const Eigen::Rotation2Dd yaw(b.yaw_deg * kDeg);
    const Eigen::Vector2d ax = yaw * Eigen::Vector2d::UnitX(), ay = yaw * Eigen::Vector2d::UnitY();
    add_slab_faces(centre - half.y() * ay, centre + half.y() * ay, 2 * half.x(), 0.0, 0.0, z0 + b.min.z(),
                   z0 + b.max.z(), PointLabel::kBox, &t.faces);
    add_slab_faces(centre - half.x() * ax, centre + half.x() * ax, 2 * half.y(), 0.0, 0.0, z0 + b.min.z(),
                   z0 + b.max.z(), PointLabel::kBox, &t.faces);
    t.surfaces.push_back({z0 + b.max.z(), 1.0});
  }
  for (const scene::Level& l : scene.levels) {
    t.surfaces.push_back({l.elevation, 1.0});
    t.surfaces.push_back({l.elevation + l.ceiling, -1.0});
    // The edge of the slab round a void, down to the ceiling of the storey below.
    double below_ceiling = -std::numeric_limits<double>::infinity();
    for (const scene::Level& other : scene.levels) {
      if (other.elevation < l.elevation)
        below_ceiling = std::max(below_ceiling, other.elevation + other.ceiling);
    }
    if (!std::isfinite(below_ceiling) || below_ceiling >= l.elevation) continue;
    for (const Polygon2& v : l.voids) {
      const double ccw = signed_area(v) > 0.0 ? 1.0 : -1.0;
      for (std::size_t i = 0; i < v.size(); ++i) {
        const Eigen::Vector2d a = v[i], b = v[(i + 1) % v.size()];
        const Eigen::Vector2d dir = (b - a).normalized();
        const Eigen::Vector2d into_void = ccw * Eigen::Vector2d(-dir.y(), dir.x());
        t.faces.push_back(
            make_face(a, dir, 0.0, (b - a).norm(), into_void, below_ceiling, l.elevation, PointLabel::kWall));
      }
    }
  }
  return t;
}

scene::Scene builtin(const std::string& name) {
  return scene::parse_scene(*scene::builtin_scene_text(name), "builtin:" + name, ".");
}

// Pieces of a face's points that no gap wider than `tolerance` separates. A sliver of wall
// seen just above a door does not join the two sides: points within kOpeningMargin of an
// opening are left out.
std::vector<std::vector<Eigen::Vector3d>> face_pieces(const std::vector<Eigen::Vector3d>& all,
                                                      const TrueFace& face, double tolerance) {
  constexpr double kOpeningMargin = 0.2;
  std::vector<Eigen::Vector3d> pts;
  for (const Eigen::Vector3d& p : all) {
    const double s = face.s_of(p);
    bool near_opening = false;
    for (const Eigen::Vector4d& o : face.openings) {
      near_opening = near_opening || (s > o[0] - kOpeningMargin && s < o[1] + kOpeningMargin &&
                                      p.z() > o[2] - kOpeningMargin && p.z() < o[3] + kOpeningMargin);
    }
    if (!near_opening) pts.push_back(p);
  }
  std::vector<bool> seen(pts.size(), false);
  std::vector<std::vector<Eigen::Vector3d>> pieces;
  for (std::size_t s = 0; s < pts.size(); ++s) {
    if (seen[s]) continue;
    std::vector<std::size_t> queue{s};
    seen[s] = true;
    for (std::size_t h = 0; h < queue.size(); ++h) {
      for (std::size_t j = 0; j < pts.size(); ++j) {
        if (!seen[j] && (pts[queue[h]] - pts[j]).norm() <= tolerance) {
          seen[j] = true;
          queue.push_back(j);
        }
      }
    }
    pieces.emplace_back();
    for (const std::size_t i : queue) pieces.back().push_back(pts[i]);
  }
  return pieces;
}

struct Scores {
  int faces_checked = 0;  // pieces of wall faces near the sensor, clearly visible
  int faces_found = 0;    // ... half covered by observations
  int faces_split = 0;    // wall faces with more observations than visible pieces
  int vertical = 0, horizontal = 0, unmatched = 0;
  int wall_obs = 0;
  double wall_angle_max = 0.0, wall_angle_sum = 0.0;  // deg
  double wall_angle_excess =
      0.0;  // the largest angle error over its face's bound (kMaxAngleErrDeg, scaled for a short face)
  double wall_offset_max = 0.0, wall_offset_sum = 0.0;   // at the centroid, m
  double wall_d_max = 0.0;                               // |d| error in the sensor frame, m
  double other_angle_max = 0.0, other_offset_max = 0.0;  // boxes, railings, void edges
  double horizontal_angle_max = 0.0, horizontal_offset_max = 0.0;
  int scans_with_floor = 0, scans = 0;
  int ceiling_points = 0, ceiling_inliers = 0;     // true ceiling points, inliers of ceiling planes
  double covered_points = 0.0, face_points = 0.0;  // wall points of checked faces in an observation
  bool finite = true, towards_sensor = true;
};

double angle_deg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b)) / kDeg;
}

// Extracts planes from the scans `scan_indices` (true poses) and scores them against the truth.
Scores score_scene(const scene::Scene& scene, const std::vector<std::size_t>& scan_indices,
                   const PlaneExtractionConfig& config) {
  const sim::Simulator sim(scene, 3);
  const Truth truth = truth_of(scene);
  const std::vector<TrueFace>& faces = truth.faces;
  Scores st;
  for (const std::size_t k : scan_indices) {
    const Pose3& T = sim.true_poses()[k];
    const PointCloud cloud = voxel_filter(sim.scan(k), kPrefilterVoxel);
    const std::vector<PlaneObservation> obs = extract_planes(cloud, T.linear(), config);
    ++st.scans;

    // The level the sensor stands on: the highest floor below it.
    double floor_z = -std::numeric_limits<double>::infinity();
    for (const scene::Level& l : scene.levels) {
      if (l.elevation < T.translation().z()) floor_z = std::max(floor_z, l.elevation);
    }
    std::vector<int> obs_per_face(faces.size(), 0);  // by the face most of its points lie on
    std::vector<std::vector<Eigen::Vector3d>> covering(
        faces.size());  // points of observations in the face's plane
    bool floor = false;
    int ceiling_inliers = 0;
    for (const PlaneObservation& o : obs) {
      st.finite = st.finite && o.plane.n.allFinite() && std::isfinite(o.plane.d) && o.centroid.allFinite() &&
                  std::isfinite(o.fit_rms);
      for (const Eigen::Vector3f& p : o.points) st.finite = st.finite && p.allFinite();
      st.towards_sensor = st.towards_sensor && o.plane.d > 0.0 && o.plane.n.dot(o.centroid) < 0.0;
      const Plane pw = o.plane.transformed(T);
      const Eigen::Vector3d cw = T * o.centroid;
      if (!o.vertical) {
        ++st.horizontal;
        bool matched = false;
        for (const TrueLevelSurface& s : truth.surfaces) {
          const Eigen::Vector3d n(0.0, 0.0, s.facing);
          if (angle_deg(pw.n, n) > kMatchAngleDeg || std::abs(cw.z() - s.z) > kMatchOffset) continue;
          matched = true;
          st.horizontal_angle_max = std::max(st.horizontal_angle_max, angle_deg(pw.n, n));
          st.horizontal_offset_max = std::max(st.horizontal_offset_max, std::abs(cw.z() - s.z));
          floor = floor || (s.facing > 0.0 && s.z == floor_z);
          if (s.facing < 0.0) ceiling_inliers += o.num_inliers;
          break;
        }
        if (!matched) ++st.unmatched;
        continue;
      }
      ++st.vertical;
      std::vector<Eigen::Vector3d> pts;
      for (const Eigen::Vector3f& p : o.points) pts.push_back(T * p.cast<double>());
      int best = -1;
      std::size_t best_count = 0;
      for (std::size_t f = 0; f < faces.size(); ++f) {
        if (angle_deg(pw.n, faces[f].plane.n) > kMatchAngleDeg) continue;
        const std::size_t on = std::count_if(pts.begin(), pts.end(), [&](const Eigen::Vector3d& p) {
          return faces[f].contains(p, kMatchOffset);
        });
        if (on > 0 && std::abs(faces[f].plane.signed_distance(cw)) <= kMatchOffset) {
          covering[f].insert(covering[f].end(), pts.begin(), pts.end());
        }
        if (on > best_count) {
          best_count = on;
          best = static_cast<int>(f);
        }
      }
      if (best < 0 || 2 * best_count < pts.size()) {
        std::printf(
            "  scan %zu: unmatched vertical plane at %.2f %.2f %.2f, normal %.2f %.2f %.2f, %d inliers\n", k,
            cw.x(), cw.y(), cw.z(), pw.n.x(), pw.n.y(), pw.n.z(), o.num_inliers);
        ++st.unmatched;
        continue;
      }
      ++obs_per_face[best];
      const TrueFace& f = faces[best];
      const double angle = angle_deg(pw.n, f.plane.n);
      const double offset = std::abs(f.plane.signed_distance(cw));
      if (f.label == kWall) {
        ++st.wall_obs;
        st.wall_angle_max = std::max(st.wall_angle_max, angle);
        const Eigen::Vector3d along = Eigen::Vector3d::UnitZ().cross(f.plane.n).normalized();
        double lo = 1e9, hi = -1e9;
        for (const Eigen::Vector3d& p : pts) {
          lo = std::min(lo, along.dot(p));
          hi = std::max(hi, along.dot(p));
        }
        const double bound = kMaxAngleErrDeg * std::max(1.0, kAngleRefExtent / std::max(hi - lo, 1e-3));
        st.wall_angle_excess = std::max(st.wall_angle_excess, angle / bound);
        st.wall_angle_sum += angle;
        st.wall_offset_max = std::max(st.wall_offset_max, offset);
        st.wall_offset_sum += offset;
        st.wall_d_max = std::max(st.wall_d_max, std::abs(f.plane.transformed(T.inverse()).d - o.plane.d));
      } else {
        st.other_angle_max = std::max(st.other_angle_max, angle);
        st.other_offset_max = std::max(st.other_offset_max, offset);
      }
    }
    st.scans_with_floor += floor ? 1 : 0;

    // True points of each wall face (world frame), from the wall-labelled points of the cloud;
    // ceiling points.
    std::vector<std::vector<Eigen::Vector3d>> face_pts(faces.size());
    int ceiling_points = 0;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
      if (cloud.points[i].norm() > config.max_range) continue;
      ceiling_points += cloud.labels[i] == static_cast<std::uint32_t>(PointLabel::kCeiling) ? 1 : 0;
      if (cloud.labels[i] != kWall) continue;
      const Eigen::Vector3d w = T * cloud.points[i].cast<double>();
      for (std::size_t f = 0; f < faces.size(); ++f) {
        if (faces[f].label == kWall && faces[f].contains(w, kOnFace)) face_pts[f].push_back(w);
      }
    }
    st.ceiling_points += ceiling_points;
    st.ceiling_inliers += ceiling_inliers;
    for (std::size_t f = 0; f < faces.size(); ++f) {
      if (face_pts[f].empty()) continue;
      const auto pieces = face_pieces(face_pts[f], faces[f], config.cluster_tolerance);
      const auto visible = std::count_if(pieces.begin(), pieces.end(), [&](const auto& piece) {
        return static_cast<int>(piece.size()) >= config.min_inliers / 2;
      });
      if (obs_per_face[f] > std::max<int>(1, static_cast<int>(visible))) {
        ++st.faces_split;
        std::printf("  scan %zu: face %zu seen as %d observations, %d pieces\n", k, f, obs_per_face[f],
                    static_cast<int>(visible));
      }
      if (faces[f].horizontal_distance(T.translation()) > kNearRange) continue;
      // Clearly visible pieces: twice the smallest face kept, over twice the smallest extent.
      for (const auto& piece : pieces) {
        double lo = std::numeric_limits<double>::max(), hi = std::numeric_limits<double>::lowest();
        for (const Eigen::Vector3d& p : piece) {
          lo = std::min(lo, faces[f].s_of(p));
          hi = std::max(hi, faces[f].s_of(p));
        }
        if (static_cast<int>(piece.size()) < 2 * config.min_inliers || hi - lo < 2 * config.min_extent)
          continue;
        ++st.faces_checked;
        std::size_t covered = 0;
        for (const Eigen::Vector3d& p : piece) {
          covered += std::any_of(covering[f].begin(), covering[f].end(), [&](const Eigen::Vector3d& q) {
            return (p - q).norm() <= config.point_voxel;
          });
        }
        st.covered_points += static_cast<double>(covered);
        st.face_points += static_cast<double>(piece.size());
        if (2 * covered >= piece.size())
          ++st.faces_found;
        else
          std::printf(
              "  scan %zu: face %zu (n %.2f %.2f, d %.2f) missed (%zu points, %.1f m long, %zu covered)\n", k,
              f, faces[f].plane.n.x(), faces[f].plane.n.y(), faces[f].plane.d, piece.size(), hi - lo,
              covered);
      }
    }
  }
  std::printf(
      "[%s, %d scans] wall faces: %d checked, %d found, %d split, point coverage %.3f; "
      "%d vertical (%d on walls), %d horizontal, %d unmatched observations\n"
      "  walls: angle err mean %.3f max %.3f deg, offset err mean %.4f max %.4f m, d err max %.4f m\n"
      "  boxes/railings: angle err max %.3f deg, offset max %.4f m; horizontal: angle max %.3f deg, "
      "offset max %.4f m; floor in %d scans; ceiling: %d inliers of %d points\n",
      scene.name.c_str(), st.scans, st.faces_checked, st.faces_found, st.faces_split,
      st.covered_points / std::max(1.0, st.face_points), st.vertical, st.wall_obs, st.horizontal,
      st.unmatched, st.wall_angle_sum / std::max(1, st.wall_obs), st.wall_angle_max,
      st.wall_offset_sum / std::max(1, st.wall_obs), st.wall_offset_max, st.wall_d_max, st.other_angle_max,
      st.other_offset_max, st.horizontal_angle_max, st.horizontal_offset_max, st.scans_with_floor,
      st.ceiling_inliers, st.ceiling_points);
  return st;
}

std::vector<std::size_t> spread(std::size_t total, std::size_t count) {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < count; ++i) out.push_back(i * total / count);
  return out;
}

void expect_good(const Scores& st, int min_faces) {
  EXPECT_GE(st.faces_checked, min_faces);
  EXPECT_EQ(st.faces_found, st.faces_checked);
  EXPECT_EQ(st.faces_split, 0);
  EXPECT_GE(st.covered_points / st.face_points, 0.9);
  EXPECT_EQ(st.unmatched, 0);
  EXPECT_LE(st.wall_angle_excess, 1.0);
  EXPECT_LE(st.wall_offset_max, kMaxOffsetErr);
  EXPECT_TRUE(st.finite);
  EXPECT_TRUE(st.towards_sensor);
  EXPECT_EQ(st.scans_with_floor, st.scans);
  EXPECT_GE(st.ceiling_inliers, st.ceiling_points / 2);
  EXPECT_LE(st.horizontal_angle_max, kMaxAngleErrDeg);
  EXPECT_LE(st.horizontal_offset_max, kMaxOffsetErr);
}

TEST(PlaneExtraction, OfficeWallFacesFoundOnceWithSmallErrors) {
  const scene::Scene scene = builtin("office");
  const sim::Simulator probe(scene, 3);
  const Scores st =
      score_scene(scene, spread(probe.num_scans() / 2, 24), PlaneExtractionConfig{});  // one lap
  expect_good(st, 40);
}

TEST(PlaneExtraction, AtriumWallFacesFoundOnceWithSmallErrors) {
  const scene::Scene scene = builtin("atrium");
  const sim::Simulator probe(scene, 3);
  const Scores st =
      score_scene(scene, spread(probe.num_scans() / 2, 16), PlaneExtractionConfig{});  // one lap
  expect_good(st, 25);
}

// Two walls in line across a gap, seen square-on from 2.9 m: the gap decides whether they are
// one face or two. The sensor heads towards the walls and may be pitched.
scene::Scene gap_scene(double gap, double tilt_deg) {
  const double a = 4.5 - 0.5 * gap, b = 4.5 + 0.5 * gap;
  const std::string text =
      "name: gap\nsensor: {preset: os1-64, tilt_deg: " + std::to_string(tilt_deg) +
      "}\n"
      "levels:\n  - {name: G, elevation: 0.0, ceiling: 3.0, slab: [[-2,-2],[11,-2],[11,8],[-2,8]]}\n"
      "walls:\n  - {level: G, from: [0, 5], to: [" +
      std::to_string(a) +
      ", 5]}\n"
      "  - {level: G, from: [" +
      std::to_string(b) +
      ", 5], to: [9, 5]}\n"
      "trajectory:\n  level: G\n  waypoints: [[4.5, 2.0], [4.5, 3.0]]\n";
  return scene::parse_scene(text, "gap.yaml", ".");
}

std::vector<PlaneObservation> walls_facing_sensor(const std::vector<PlaneObservation>& obs, const Pose3& T) {
  std::vector<PlaneObservation> out;
  for (const PlaneObservation& o : obs) {
    if (o.vertical &&
        o.plane.transformed(T).n.dot(-Eigen::Vector3d::UnitY()) > std::cos(kMaxAngleErrDeg * kDeg)) {
      out.push_back(o);
    }
  }
  return out;
}

TEST(PlaneExtraction, GapWiderThanToleranceSplitsCollinearWalls) {
  const PlaneExtractionConfig config;
  for (const double gap : {1.0, 0.6, 0.2}) {
    const sim::Simulator sim(gap_scene(gap, 0.0), 5);
    const Pose3 T = sim.true_poses()[0];
    const PointCloud cloud = voxel_filter(sim.scan(0), kPrefilterVoxel);
    const std::vector<PlaneObservation> faces =
        walls_facing_sensor(extract_planes(cloud, T.linear(), config), T);
    const std::size_t expected = gap > config.cluster_tolerance ? 2 : 1;
    ASSERT_EQ(faces.size(), expected) << "gap " << gap;
    for (const PlaneObservation& f : faces) {
      const Plane pw = f.plane.transformed(T);  // the face y = 4.9, normal -y
      EXPECT_LE(angle_deg(pw.n, -Eigen::Vector3d::UnitY()), kMaxAngleErrDeg);
      EXPECT_NEAR(pw.d, 4.9, kMaxOffsetErr);
    }
    if (expected == 2) {  // one on each side of the gap
      const double x0 = (T * faces[0].centroid).x(), x1 = (T * faces[1].centroid).x();
      EXPECT_LT(std::min(x0, x1), 4.5);
      EXPECT_GT(std::max(x0, x1), 4.5);
    }
  }
}

TEST(PlaneExtraction, ClassesAreJudgedInTheMapFrame) {
  // A sensor pitched 20 degrees towards the walls: its walls are vertical and its floor
  // horizontal only once rotated into the map frame.
  constexpr double kTiltDeg = 20.0;
  const PlaneExtractionConfig config;
  const sim::Simulator sim(gap_scene(1.0, kTiltDeg), 5);
  const Pose3 T = sim.true_poses()[0];
  ASSERT_NEAR(std::acos(T.linear()(2, 2)) / kDeg, kTiltDeg, 0.1);
  const PointCloud cloud = voxel_filter(sim.scan(0), kPrefilterVoxel);
  const std::vector<PlaneObservation> planes = extract_planes(cloud, T.linear(), config);
  EXPECT_EQ(walls_facing_sensor(planes, T).size(), 2u);
  bool floor = false;
  for (const PlaneObservation& o : planes) {
    const Plane pw = o.plane.transformed(T);
    if (!o.vertical && pw.n.z() > std::cos(kMaxAngleErrDeg * kDeg) && std::abs(pw.d) < kMaxOffsetErr)
      floor = true;
  }
  EXPECT_TRUE(floor);
  // Taken as level, the same scan has its walls and floor tilted by 20 degrees: neither class.
  for (const PlaneObservation& o : extract_planes(cloud, Eigen::Matrix3d::Identity(), config)) {
    const Plane pw = o.plane.transformed(T);
    EXPECT_FALSE(o.vertical && std::abs(pw.n.y()) > std::cos(kMaxAngleErrDeg * kDeg));
    EXPECT_FALSE(!o.vertical && pw.n.z() > std::cos(kMaxAngleErrDeg * kDeg));
  }
}

TEST(PlaneExtraction, TooFewPointsGiveNoPlanes) {
  const PlaneExtractionConfig config;
  EXPECT_TRUE(extract_planes(PointCloud{}, Eigen::Matrix3d::Identity(), config).empty());
  // A 1 m x 1 m patch of wall at 0.1 m spacing: 100 points, fewer than min_inliers.
  PointCloud patch;
  for (int i = 0; i < 10; ++i) {
    for (int j = 0; j < 10; ++j) patch.points.emplace_back(3.0f, 0.1f * i, 0.1f * j);
  }
  ASSERT_LT(static_cast<int>(patch.size()), config.min_inliers);
  EXPECT_TRUE(extract_planes(patch, Eigen::Matrix3d::Identity(), config).empty());
  // Non-finite points only.
  PointCloud bad;
  bad.points.assign(500, Eigen::Vector3f::Constant(std::numeric_limits<float>::quiet_NaN()));
  bad.points.insert(bad.points.end(), 500, Eigen::Vector3f::Constant(std::numeric_limits<float>::infinity()));
  EXPECT_TRUE(extract_planes(bad, Eigen::Matrix3d::Identity(), config).empty());
}

TEST(PlaneExtraction, NonFinitePointsAreIgnoredAndOutputIsDeterministic) {
  const PlaneExtractionConfig config;
  const scene::Scene scene = builtin("office");
  const sim::Simulator sim(scene, 3);
  const Pose3 T = sim.true_poses()[40];
  const PointCloud clean = voxel_filter(sim.scan(40), kPrefilterVoxel);
  PointCloud dirty;
  for (std::size_t i = 0; i < clean.size(); ++i) {
    dirty.points.push_back(clean.points[i]);
    if (i % 7 == 0) dirty.points.emplace_back(std::numeric_limits<float>::quiet_NaN(), 1.0f, 1.0f);
    if (i % 11 == 0) dirty.points.emplace_back(1.0f, -std::numeric_limits<float>::infinity(), 0.0f);
  }
  const std::vector<PlaneObservation> a = extract_planes(clean, T.linear(), config);
  const std::vector<PlaneObservation> b = extract_planes(dirty, T.linear(), config);
  const std::vector<PlaneObservation> c = extract_planes(clean, T.linear(), config);
  ASSERT_GE(a.size(), 5u);
  for (const auto* other : {&b, &c}) {
    ASSERT_EQ(other->size(), a.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
      EXPECT_EQ((*other)[i].plane.n, a[i].plane.n);
      EXPECT_EQ((*other)[i].plane.d, a[i].plane.d);
      EXPECT_EQ((*other)[i].num_inliers, a[i].num_inliers);
      EXPECT_EQ((*other)[i].points, a[i].points);
    }
  }
  // Largest first, and never more than max_planes.
  for (std::size_t i = 1; i < a.size(); ++i) EXPECT_GE(a[i - 1].num_inliers, a[i].num_inliers);
  PlaneExtractionConfig few = config;
  few.max_planes = 3;
  const std::vector<PlaneObservation> top = extract_planes(clean, T.linear(), few);
  ASSERT_EQ(top.size(), 3u);
  for (std::size_t i = 0; i < top.size(); ++i) EXPECT_EQ(top[i].num_inliers, a[i].num_inliers);
}

// Real HDL-32e returns (a campus walkway): the planes of two consecutive scans agree through
// the known relative pose (target <- source), and the ground comes out horizontal under the
// sensor. The target scan is taken as level; the source is rotated into its frame.
TEST(PlaneExtraction, RealScansGiveRepeatablePlanes) {
  const std::string dir = std::string(TSGRAPHS_TEST_DATA_DIR) + "/hdl32_pair/";
  const PointCloud target = voxel_filter(io::read_pcd(dir + "251370668.pcd"), kPrefilterVoxel);
  const PointCloud source = voxel_filter(io::read_pcd(dir + "251371071.pcd"), kPrefilterVoxel);
  Eigen::Matrix4d m;
  std::ifstream in(dir + "relative.txt");
  for (int i = 0; i < 16; ++i) in >> m(i / 4, i % 4);
  ASSERT_TRUE(in);
  Pose3 T_target_source;
  T_target_source.matrix() = m;

  const PlaneExtractionConfig config;
  const std::vector<PlaneObservation> a = extract_planes(target, Eigen::Matrix3d::Identity(), config);
  const std::vector<PlaneObservation> b = extract_planes(source, T_target_source.linear(), config);
  std::printf("[hdl32] %zu and %zu points -> %zu and %zu planes\n", target.size(), source.size(), a.size(),
              b.size());
  ASSERT_GE(a.size(), 3u);
  int matched = 0, large = 0;
  double max_angle = 0.0, max_offset = 0.0;
  for (const PlaneObservation& o : b) {
    if (o.num_inliers < 2 * config.min_inliers) continue;
    ++large;
    const Plane p = o.plane.transformed(T_target_source);
    const Eigen::Vector3d c = T_target_source * o.centroid;
    double best_angle = kMatchAngleDeg, best_offset = kMatchOffset;
    bool found = false;
    for (const PlaneObservation& q : a) {
      const double angle = angle_deg(p.n, q.plane.n), offset = std::abs(q.plane.signed_distance(c));
      if (q.vertical == o.vertical && angle <= kMatchAngleDeg && offset <= kMatchOffset &&
          angle + offset < best_angle + best_offset) {
        best_angle = angle;
        best_offset = offset;
        found = true;
      }
    }
    if (!found) continue;
    ++matched;
    max_angle = std::max(max_angle, best_angle);
    max_offset = std::max(max_offset, best_offset);
  }
  std::printf(
      "[hdl32] %d of %d large source planes matched in the target, angle max %.3f deg, offset max %.4f m\n",
      matched, large, max_angle, max_offset);
  EXPECT_GE(large, 3);
  EXPECT_GE(matched, large - 1);
  // Within 1 degree and 5 cm: the relative pose is itself a registration result, and some
  // of these surfaces are rough (fit_rms up to 2 cm).
  EXPECT_LE(max_angle, 1.0);
  EXPECT_LE(max_offset, 0.05);
  // The ground: a large horizontal plane below the sensor (which is pitched about 6 degrees).
  bool ground = false;
  for (const PlaneObservation& o : a) {
    ground = ground || (!o.vertical && o.plane.n.z() > std::cos(10.0 * kDeg) &&
                        o.num_inliers >= 2 * config.min_inliers);
  }
  EXPECT_TRUE(ground);
}

}  // namespace
