#pragma once
// Synthetic ground truth for the back-end's tests: a square corridor loop driven twice with
// drifting odometry, its walls and floor seen with small noise, as the graph a front end makes.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "tsgraphs/graph/situational_graph.hpp"

namespace tsgraphs::graph::test {

constexpr double kDeg = M_PI / 180.0;
constexpr double kLoopWidth = 20.0, kLoopHeight = 10.0;  // centre line of the corridor loop (m)
constexpr double kLap = 2.0 * (kLoopWidth + kLoopHeight);
constexpr int kLaps = 2;
constexpr double kHalfWidth = 1.5;  // corridor half width (m)
// A keyframe sees the wall faces in front of it nearer than this (m): far enough to see the end
// of its corridor, short of the 11.5 m across the inner block (that would see through it).
constexpr double kWallRange = 10.0;
constexpr double kOdomSigmaTrans = 0.02, kOdomSigmaYawDeg = 0.2;  // per 1 m step
constexpr double kPlaneNoiseDeg = 0.2, kPlaneNoiseDist = 0.01;
constexpr unsigned kSeed = 2;  // its odometry ends 0.50 m and 3.1 deg off

constexpr double kSensorHeight = 0.5;  // above the floor (m)

struct Surface {
  Plane plane;           ///< map frame, normal towards the corridor
  bool vertical = true;  ///< a wall; false: the floor, seen from everywhere
  Eigen::Vector2d from = Eigen::Vector2d::Zero(),
                  to = Eigen::Vector2d::Zero();  ///< a wall's extent
};

struct Scenario {
  std::vector<Pose3> truth;
  std::vector<Surface> surfaces;
  std::vector<int> plane_of;  ///< graph plane id of each surface, -1 if never seen
  SituationalGraph graph;
};

// Pose at arc length s on the rectangle (anticlockwise from the origin, heading along it).
inline Pose3 loop_pose(double s) {
  s = std::fmod(s, kLap);
  if (s < kLoopWidth) return make_pose({s, 0, 0}, 0.0);
  s -= kLoopWidth;
  if (s < kLoopHeight) return make_pose({kLoopWidth, s, 0}, M_PI / 2);
  s -= kLoopHeight;
  if (s < kLoopWidth) return make_pose({kLoopWidth - s, kLoopHeight, 0}, M_PI);
  s -= kLoopWidth;
  return make_pose({0, kLoopHeight - s, 0}, -M_PI / 2);
}

inline Surface wall(Eigen::Vector2d from, Eigen::Vector2d to, Eigen::Vector2d normal) {
  const Eigen::Vector3d n(normal.x(), normal.y(), 0.0);
  return {Plane::from_point_normal(Eigen::Vector3d(from.x(), from.y(), 0.0), n), true, from, to};
}

// The floor, then the outer and inner wall faces of the corridor round the rectangle.
inline std::vector<Surface> loop_surfaces() {
  const double h = kHalfWidth, W = kLoopWidth, H = kLoopHeight;
  Surface floor;
  floor.plane = Plane::from_point_normal({0, 0, -kSensorHeight}, {0, 0, 1});
  floor.vertical = false;
  return {floor,
          wall({-h, -h}, {W + h, -h}, {0, 1}),
          wall({-h, H + h}, {W + h, H + h}, {0, -1}),
          wall({-h, -h}, {-h, H + h}, {1, 0}),
          wall({W + h, -h}, {W + h, H + h}, {-1, 0}),
          wall({h, h}, {W - h, h}, {0, -1}),
          wall({h, H - h}, {W - h, H - h}, {0, 1}),
          wall({h, h}, {h, H - h}, {-1, 0}),
          wall({W - h, h}, {W - h, H - h}, {1, 0})};
}

inline bool sees(const Surface& w, const Eigen::Vector3d& p) {
  if (!w.vertical) return true;
  const Eigen::Vector2d dir = (w.to - w.from).normalized();
  const double along = dir.dot(p.head<2>() - w.from);
  const double distance = w.plane.signed_distance(p);
  return distance > 0.0 && distance < kWallRange && along >= 0.0 && along <= (w.to - w.from).norm();
}

// Builds the graph a front end would: keyframes at the odometry, each surface mapped from its first
// observation, then every observation as a plane edge.
inline void fill_graph(Scenario& s, const std::vector<Pose3>& odom, bool with_planes, std::mt19937& rng) {
  std::normal_distribution<double> angle(0.0, kPlaneNoiseDeg * kDeg), dist(0.0, kPlaneNoiseDist);
  for (std::size_t k = 0; k < s.truth.size(); ++k) {
    KeyframeNode node;
    node.scan_index = k;
    node.pose = odom[k];
    node.odom = odom[k];
    node.accum_distance = double(k);  // a keyframe every metre
    s.graph.add_keyframe(node);
    if (k > 0) s.graph.add_odometry_edge({int(k) - 1, int(k), odom[k - 1].inverse() * odom[k]});
  }
  s.plane_of.assign(s.surfaces.size(), -1);
  if (!with_planes) return;
  for (std::size_t k = 0; k < s.truth.size(); ++k) {
    for (std::size_t w = 0; w < s.surfaces.size(); ++w) {
      if (!sees(s.surfaces[w], s.truth[k].translation())) continue;
      Plane measured = s.surfaces[w].plane.transformed(s.truth[k].inverse());
      const double tz = angle(rng), ty = angle(rng), tx = angle(rng);  // the last first, as gcc drew them
      const Eigen::Vector3d tilt(tx, ty, tz);
      measured.n = Eigen::AngleAxisd(tilt.norm(), tilt.normalized()) * measured.n;
      measured.d += dist(rng);
      if (s.plane_of[w] < 0)
        s.plane_of[w] = s.graph.add_plane(measured.transformed(odom[k]), s.surfaces[w].vertical);
      s.graph.add_plane_edge({int(k), s.plane_of[w], measured, 100});
    }
  }
}

// Two laps of the corridor loop, a keyframe every metre, ending where it started.
inline Scenario corridor_loop(bool with_planes) {
  Scenario s;
  s.surfaces = loop_surfaces();
  const int n = int(kLaps * kLap) + 1;
  for (int k = 0; k < n; ++k) s.truth.push_back(loop_pose(k));
  std::mt19937 rng(kSeed);
  std::normal_distribution<double> trans(0.0, kOdomSigmaTrans), yaw(0.0, kOdomSigmaYawDeg * kDeg);
  std::vector<Pose3> odom{s.truth[0]};
  for (int k = 1; k < n; ++k) {
    Pose3 step = s.truth[k - 1].inverse() * s.truth[k];
    const double sy = trans(rng), sx = trans(rng);  // the last first, as gcc drew them
    step.translation() += Eigen::Vector3d(sx, sy, 0);
    step.linear() = Eigen::AngleAxisd(yaw(rng), Eigen::Vector3d::UnitZ()) * step.linear();
    odom.push_back(odom.back() * step);
  }
  fill_graph(s, odom, with_planes, rng);
  return s;
}

inline double position_rmse(const SituationalGraph& g, const std::vector<Pose3>& truth) {
  double sum = 0.0;
  for (std::size_t k = 0; k < truth.size(); ++k)
    sum += (g.keyframes()[k].pose.translation() - truth[k].translation()).squaredNorm();
  return std::sqrt(sum / double(truth.size()));
}

inline double end_error(const SituationalGraph& g, const std::vector<Pose3>& truth) {
  return (g.keyframes().back().pose.translation() - truth.back().translation()).norm();
}

struct PlaneErrors {
  double max_angle_deg = 0.0, max_distance = 0.0;
};

inline PlaneErrors plane_errors(const Scenario& s) {
  PlaneErrors e;
  for (std::size_t w = 0; w < s.surfaces.size(); ++w) {
    if (s.plane_of[w] < 0) continue;
    const Plane& est = s.graph.planes().at(s.plane_of[w]).plane;
    const Plane& gt = s.surfaces[w].plane;
    e.max_angle_deg = std::max(e.max_angle_deg, std::acos(std::min(1.0, est.n.dot(gt.n))) / kDeg);
    e.max_distance = std::max(e.max_distance, std::abs(est.d - gt.d));
  }
  return e;
}

inline bool same_bits(const Pose3& a, const Pose3& b) {
  return std::memcmp(a.matrix().data(), b.matrix().data(), sizeof(double) * 16) == 0;
}

inline bool same_bits(const Plane& a, const Plane& b) {
  return std::memcmp(a.n.data(), b.n.data(), sizeof(double) * 3) == 0 &&
         std::memcmp(&a.d, &b.d, sizeof(double)) == 0;
}

}  // namespace tsgraphs::graph::test
