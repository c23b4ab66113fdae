#include "tsgraphs/scene/trajectory.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "tsgraphs/scene/scene_geometry.hpp"

namespace tsgraphs::scene {
namespace {

constexpr double kHeightStep = 0.05;                     // m of travel between samples of the surface height
constexpr double kMaxArcTurnRad = 170.0 * M_PI / 180.0;  // sharper corners turn in place
constexpr double kMinTurnRad = 1e-6;                     // straighter corners need no turn at all
constexpr double kMaxStep = 0.25;  // m of height change between two samples that is a fall, not a slope

double heading(const Vec2& a, const Vec2& b) { return std::atan2(b.y() - a.y(), b.x() - a.x()); }

}  // namespace

Trajectory::Trajectory(const Scene& scene)
    : speed_(scene.trajectory.speed),
      yaw_rate_(scene.trajectory.yaw_rate_deg * M_PI / 180.0),
      mount_height_(scene.sensor.mount_height),
      height_step_(kHeightStep) {
  const TrajectorySpec& spec = scene.trajectory;
  std::vector<Vec2> lap;
  for (const Waypoint& w : spec.waypoints) lap.push_back(w.xy);
  // The polyline over all laps, and the polyline index where each lap starts.
  std::vector<Vec2> path = {lap.front()};
  std::vector<std::size_t> lap_vertex = {0};
  for (int k = 0; k < spec.laps; ++k) {
    if (k > 0) lap_vertex.push_back(path.size() - 1);
    if (spec.closed) {
      for (std::size_t i = 1; i < lap.size(); ++i) path.push_back(lap[i]);
      path.push_back(lap.front());
    } else {
      // An open path is walked out and back: odd laps return along it.
      const bool forward = k % 2 == 0;
      for (std::size_t i = 1; i < lap.size(); ++i) path.push_back(forward ? lap[i] : lap[lap.size() - 1 - i]);
    }
  }
  const double radius = speed_ / yaw_rate_;
  const std::size_t m = path.size();
  // Tangent length cut from each side of each corner, or -1 for a turn in place.
  std::vector<double> cut(m, 0.0);
  std::vector<double> turn(m, 0.0);
  for (std::size_t i = 1; i + 1 < m; ++i) {
    turn[i] = wrap_angle(heading(path[i], path[i + 1]) - heading(path[i - 1], path[i]));
    if (std::abs(turn[i]) < kMinTurnRad) continue;
    const double t = radius * std::tan(0.5 * std::abs(turn[i]));
    const double room = 0.5 * std::min((path[i] - path[i - 1]).norm(), (path[i + 1] - path[i]).norm());
    cut[i] = (std::abs(turn[i]) <= kMaxArcTurnRad && t <= room) ? t : -1.0;
  }
  std::size_t lap_index = 0;
  for (std::size_t i = 0; i + 1 < m; ++i) {
    if (lap_index < lap_vertex.size() && lap_vertex[lap_index] == i) {
      // A lap starts at this corner: at the arc's middle or when the turn in place begins.
      lap_starts_.push_back(
          i == 0 ? 0.0 : (cut[i] > 0.0 ? duration_ - 0.5 * std::abs(turn[i]) / yaw_rate_ : duration_));
      ++lap_index;
    }
    if (i > 0 && cut[i] < 0.0) {
      add_turn(path[i], heading(path[i - 1], path[i]), turn[i]);
      ++in_place_turns_;
    }
    const Vec2 dir = (path[i + 1] - path[i]).normalized();
    const Vec2 a = path[i] + std::max(cut[i], 0.0) * dir;
    const Vec2 b = path[i + 1] - std::max(cut[i + 1], 0.0) * dir;
    add_line(a, b);
    if (i + 2 < m && cut[i + 1] > 0.0) {
      const double h = heading(path[i], path[i + 1]);
      const Vec2 normal = turn[i + 1] > 0 ? Vec2(-dir.y(), dir.x()) : Vec2(dir.y(), -dir.x());
      add_arc(b + radius * normal, radius, h, turn[i + 1]);
      ++arc_turns_;
    }
  }
  plan_heights(scene);
}

void Trajectory::add_line(const Vec2& a, const Vec2& b) {
  const double len = (b - a).norm();
  pieces_.push_back({Piece::kLine, duration_, len / speed_, length_, a, b, heading(a, b), 0.0, 0.0});
  duration_ += len / speed_;
  length_ += len;
}

void Trajectory::add_arc(const Vec2& centre, double radius, double yaw0, double dyaw) {
  const double len = radius * std::abs(dyaw);
  pieces_.push_back({Piece::kArc, duration_, len / speed_, length_, centre, centre, yaw0, dyaw, radius});
  duration_ += len / speed_;
  length_ += len;
}

void Trajectory::add_turn(const Vec2& p, double yaw0, double dyaw) {
  const double dt = std::abs(dyaw) / yaw_rate_;
  pieces_.push_back({Piece::kTurn, duration_, dt, length_, p, p, yaw0, dyaw, 0.0});
  duration_ += dt;
}

Vec2 Trajectory::xy_at(const Piece& p, double u, double* yaw) const {
  switch (p.kind) {
    case Piece::kLine:
      *yaw = p.yaw0;
      return p.p0 + u * (p.p1 - p.p0);
    case Piece::kArc: {
      *yaw = p.yaw0 + u * p.dyaw;
      // The centre lies to the left of the heading for a left turn, to the right otherwise.
      const double side = p.dyaw > 0 ? -M_PI_2 : M_PI_2;
      return p.p0 + p.radius * Vec2(std::cos(*yaw + side), std::sin(*yaw + side));
    }
    case Piece::kTurn:
      break;
  }
  *yaw = p.yaw0 + u * p.dyaw;
  return p.p0;
}

const Trajectory::Piece& Trajectory::piece_at(double t) const {
  auto it =
      std::upper_bound(pieces_.begin(), pieces_.end(), t, [](double v, const Piece& p) { return v < p.t0; });
  return it == pieces_.begin() ? *it : *std::prev(it);
}

Pose3 Trajectory::body_pose(double t) const {
  t = std::clamp(t, 0.0, duration_);
  const Piece& p = piece_at(t);
  const double u = p.duration > 0.0 ? std::clamp((t - p.t0) / p.duration, 0.0, 1.0) : 1.0;
  double yaw;
  const Vec2 xy = xy_at(p, u, &yaw);
  return make_pose({xy.x(), xy.y(), height_at(distance_at(t)) + mount_height_}, wrap_angle(yaw));
}

double Trajectory::distance_at(double t) const {
  t = std::clamp(t, 0.0, duration_);
  const Piece& p = piece_at(t);
  if (p.kind == Piece::kTurn || p.duration <= 0.0) return p.s0;
  return p.s0 + std::min(t - p.t0, p.duration) * speed_;
}

int Trajectory::lap_at(double t) const {
  const auto it = std::upper_bound(lap_starts_.begin(), lap_starts_.end(), t);
  return std::max(0, static_cast<int>(it - lap_starts_.begin()) - 1);
}

void Trajectory::plan_heights(const Scene& scene) {
  // March along the path and follow the walkable surface closest to the last height, so a
  // ramp carries the sensor from one level to the next and it never jumps between storeys.
  const std::size_t n = static_cast<std::size_t>(std::ceil(length_ / height_step_)) + 1;
  heights_.assign(n, 0.0);
  double z = scene.levels[scene.trajectory.level].elevation;
  std::size_t k = 0;
  bool was_off = false;
  for (const Piece& p : pieces_) {
    if (p.kind == Piece::kTurn) continue;
    const double len = p.duration * speed_;
    for (; k < n && k * height_step_ <= p.s0 + len + 1e-9; ++k) {
      const double u = len > 0.0 ? std::clamp((k * height_step_ - p.s0) / len, 0.0, 1.0) : 1.0;
      double yaw;
      const Vec2 xy = xy_at(p, u, &yaw);
      double best_gap = std::numeric_limits<double>::infinity();
      double best = z;
      for (std::size_t l = 0; l < scene.levels.size(); ++l) {
        double zl;
        if (walkable_height(scene, static_cast<int>(l), xy, &zl) && std::abs(zl - z) < best_gap) {
          best_gap = std::abs(zl - z);
          best = zl;
        }
      }
      char where[160];
      const bool off = !std::isfinite(best_gap);
      if (off && !was_off) {
        std::snprintf(where, sizeof(where), "the path leaves every walkable surface at [%.2f, %.2f]", xy.x(),
                      xy.y());
        warnings_.emplace_back(where);
      } else if (!off && k > 0 && best_gap > kMaxStep) {
        std::snprintf(where, sizeof(where),
                      "the path %s %.2f m at [%.2f, %.2f] (off a ramp's side or into a void?)",
                      best < z ? "drops" : "jumps up", std::abs(best - z), xy.x(), xy.y());
        warnings_.emplace_back(where);
      }
      was_off = off;
      z = best;  // off every surface: keep the last height
      heights_[k] = z;
    }
  }
  for (; k < n; ++k) heights_[k] = z;
}

double Trajectory::height_at(double s) const {
  if (heights_.empty()) return 0.0;
  const double f = std::clamp(s / height_step_, 0.0, static_cast<double>(heights_.size() - 1));
  const std::size_t i = static_cast<std::size_t>(f);
  if (i + 1 >= heights_.size()) return heights_.back();
  return heights_[i] + (f - i) * (heights_[i + 1] - heights_[i]);
}

}  // namespace tsgraphs::scene
