#pragma once
/// The sensor's path through a scene: straight segments at constant speed, corners taken on
/// an arc whose curvature keeps the turn rate at `yaw_rate_deg` (or, where the arc does not
/// fit between the corner's neighbours, a turn in place), repeated for `laps`. The height
/// follows the walkable surface (slabs and ramps) under the path.
#include <string>
#include <vector>

#include "tsgraphs/core/pose.hpp"
#include "tsgraphs/scene/scene.hpp"

namespace tsgraphs::scene {

class Trajectory {
 public:
  /// Plans the path of `scene.trajectory` (laps included).
  explicit Trajectory(const Scene& scene);

  double duration() const { return duration_; }
  /// Horizontal distance travelled over all laps, m.
  double length() const { return length_; }
  /// Start time of each lap (the first is 0).
  const std::vector<double>& lap_starts() const { return lap_starts_; }
  /// Number of corners taken on an arc and turned in place.
  int arc_turns() const { return arc_turns_; }
  int turns_in_place() const { return in_place_turns_; }

  /// Pose of the body at time t (clamped to [0, duration]): x forward along the path, z up,
  /// at the sensor's mount height above the walkable surface, no tilt.
  Pose3 body_pose(double t) const;
  /// Distance travelled at time t.
  double distance_at(double t) const;
  /// Lap index (0-based) at time t.
  int lap_at(double t) const;
  /// Places where the planned path leaves the walkable surface: a drop or a climb of more
  /// than a step (off a ramp's side, into a void) or no surface at all under it. Empty for a
  /// sound scene; front ends print them.
  const std::vector<std::string>& warnings() const { return warnings_; }

 private:
  struct Piece {
    enum Kind { kLine, kArc, kTurn } kind;
    double t0, duration;
    double s0;          // distance travelled at the start
    Vec2 p0, p1;        // line: ends; arc: centre in p0; turn: place in p0
    double yaw0, dyaw;  // heading at start and signed change
    double radius;      // arc
  };
  void add_line(const Vec2& a, const Vec2& b);
  void add_arc(const Vec2& centre, double radius, double yaw0, double dyaw);
  void add_turn(const Vec2& p, double yaw0, double dyaw);
  void plan_heights(const Scene& scene);
  const Piece& piece_at(double t) const;
  /// Position at fraction u of a piece; `yaw` gets the heading there.
  Vec2 xy_at(const Piece& p, double u, double* yaw) const;
  double height_at(double s) const;

  double speed_;
  double yaw_rate_;
  double mount_height_;
  std::vector<Piece> pieces_;
  std::vector<double> lap_starts_;
  double duration_ = 0.0;
  double length_ = 0.0;
  int arc_turns_ = 0;
  int in_place_turns_ = 0;
  double height_step_;           // spacing of the height profile, m
  std::vector<double> heights_;  // surface height every height_step_ metres of travel
  std::vector<std::string> warnings_;
};

}  // namespace tsgraphs::scene
