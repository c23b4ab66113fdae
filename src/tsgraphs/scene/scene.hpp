#pragma once
/// A building, the LiDAR that scans it and the path it travels: the simulator's input
/// (docs/scene-format.md). Plain data; `load_scene` reads and validates it.
#include <cstdint>
#include <Eigen/Core>
#include <string>
#include <vector>

#include "tsgraphs/core/polygon.hpp"

namespace tsgraphs::scene {

/// The LiDAR model. Defaults are the scene format's (an OS1-64-like sensor).
struct SensorSpec {
  std::string preset;                   ///< os1-64 | os0-128 | vlp-16 | hesai-xt32, or "" when given by hand
  int channels = 64;                    ///< rows of the scan
  int columns = 1024;                   ///< firings per revolution
  double vertical_fov_min_deg = -22.5;  ///< lowest beam
  double vertical_fov_max_deg = 22.5;   ///< highest beam
  /// Elevation of each beam, top to bottom, degrees. Filled by the loader from the preset's
  /// published table, from `vertical_angles_deg`, or evenly over the field of view.
  std::vector<double> vertical_angles_deg;
  double max_range = 60.0;  ///< returns beyond are lost, m
  double min_range = 0.3;   ///< returns closer are lost, m
  double rate_hz = 10.0;    ///< revolutions (sweeps) per second
  double record_hz =
      0.0;  ///< scans kept per second, <= rate_hz (a recording of every n-th sweep); 0: rate_hz
  double range_noise_std = 0.015;  ///< gaussian range noise, m
  double dropout = 0.0;            ///< probability that a return is lost
  double mount_height = 0.55;      ///< sensor above the walkable surface, m
  double tilt_deg = 0.0;           ///< pitch about the sensor's y axis
};

/// What carries the sensor (scene format `platform:`): the motion it adds to the path's, and
/// whether a scan is swept over its period.
enum class PlatformType { kWheeled, kHandheld, kLegged };
struct PlatformSpec {
  PlatformType type = PlatformType::kWheeled;
  double bob = 0.0;             ///< m, amplitude of the vertical bob, once per step
  double step_hz = 0.0;         ///< steps per second: bob and pitch at this rate, roll at half of it
  double sway_deg = 0.0;        ///< amplitude of the roll sway (pitch: half of it)
  double yaw_jitter_deg = 0.0;  ///< amplitude of the heading's wander about the path's
  double vibration = 0.0;       ///< m, amplitude of the mount's vertical vibration (a trot's impacts)
  double vibration_hz = 0.0;    ///< its frequency
  bool motion_distortion =
      false;  ///< a scan is swept over its period, each column at its time (per-point times)
};

/// How odometry drifts from truth: random walks, std growing with sqrt(distance or angle).
struct OdometryNoise {
  double trans_noise_per_m = 0.01;  ///< translation std per axis after 1 m (sqrt(m) scaling)
  double yaw_noise_per_rad = 0.01;  ///< yaw std after turning 1 rad
  double yaw_noise_per_m = 0.002;   ///< yaw std after travelling 1 m
};

struct Level {
  std::string name;
  double elevation = 0.0;       ///< z of the walkable floor surface
  double ceiling = 3.0;         ///< ceiling height above the floor surface
  Polygon2 slab;                ///< outline of the walkable floor
  std::vector<Polygon2> voids;  ///< holes in the slab, open to the storey below
  int line = 0;                 ///< line in the scene file, for messages
};

struct Opening {
  double at = 0.0;  ///< distance of the opening's centre from the wall's `from`
  double width = 0.9;
  double height = 2.1;
  double sill = 0.0;  ///< 0 for a door
  /// A glass pane filling the opening: the probability that a ray passes it (a return behind
  /// it), as a glass railing's; 1 (the default): no pane, an open door or window.
  double transmission = 1.0;
};

struct Wall {
  int level = 0;                                ///< index into Scene::levels
  Vec2 from = Vec2::Zero(), to = Vec2::Zero();  ///< centre line
  double thickness = 0.2;
  double height = 3.0;
  std::vector<Opening> openings;
  /// Set by the loader where this end meets the end of another wall of the level: the wall
  /// then reaches half its thickness past the end, so that the corner is closed.
  bool joined_from = false, joined_to = false;
  int line = 0;
};

/// solid: a panel; bars: posts and a top rail; glass: a panel the LiDAR partly sees through.
enum class RailingStyle { kSolid, kBars, kGlass };

struct Railing {
  int level = 0;
  Vec2 from = Vec2::Zero(), to = Vec2::Zero();
  double height = 1.0;
  RailingStyle style = RailingStyle::kSolid;
  double transmission = 0.8;  ///< glass: probability that a ray passes through (a return behind it)
  int line = 0;
};

struct Box {
  int level = 0;
  Eigen::Vector3d min = Eigen::Vector3d::Zero();  ///< relative to the level's elevation
  Eigen::Vector3d max = Eigen::Vector3d::Zero();
  double yaw_deg = 0.0;  ///< rotation about the box centre
  std::string label;     ///< free text (bookshelf, pillar, ...)
  int line = 0;
};

/// Box label of a door's leaf (generate --realistic hangs them; drawings show them as doors).
inline constexpr const char* kDoorLeafLabel = "door";

/// Point label given to the cubes of a voxel map.
enum class VoxelLabel { kWall, kBox, kRailing, kAuto };

struct VoxelMap {
  std::string file;         ///< resolved path of the PCD
  double voxel_size = 0.1;  ///< edge of each cube
  int level = 0;
  VoxelLabel label = VoxelLabel::kAuto;
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
  double yaw_deg = 0.0;  ///< rotation about z, applied before the offset
  int line = 0;
};

struct Ramp {
  int from_level = 0;         ///< the ramp's low end is at this level's elevation
  int to_level = 0;           ///< its high end at this one's
  Polygon2 polygon;           ///< footprint
  Vec2 axis = Vec2::UnitY();  ///< unit direction of ascent
  int line = 0;
};

struct Room {
  std::string name;
  int level = 0;
  Polygon2 polygon;
};

/// A person walking through the scans (a moving obstacle): a vertical cylinder standing on its
/// level's floor, walking its path to the end and back, over and over.
struct Person {
  int level = 0;
  std::vector<Vec2> path;  ///< two or more points
  double speed = 1.2;      ///< m/s
  double offset = 0.0;     ///< m walked along path (there and back) at time 0
  double height = 1.75;
  double radius = 0.25;
  int line = 0;
};

struct Waypoint {
  Vec2 xy = Vec2::Zero();
  int level = 0;  ///< the level the waypoint stands on
  int line = 0;
};

struct TrajectorySpec {
  int level = 0;  ///< level of the first waypoint
  std::vector<Waypoint> waypoints;
  bool closed = true;          ///< return to the first waypoint at the end of each lap
  int laps = 2;                ///< repeats of the path
  double speed = 1.0;          ///< m/s, horizontal
  double yaw_rate_deg = 90.0;  ///< max turn rate, deg/s
};

struct Scene {
  std::string name;
  std::uint64_t seed = 0;
  SensorSpec sensor;
  PlatformSpec platform;
  OdometryNoise odometry;
  std::vector<Level> levels;
  std::vector<Wall> walls;
  std::vector<Railing> railings;
  std::vector<Box> boxes;
  std::vector<VoxelMap> voxel_maps;
  std::vector<Ramp> ramps;
  std::vector<Room> rooms;
  std::vector<Person> people;
  TrajectorySpec trajectory;
  std::string file;         ///< the scene file it was loaded from (or "builtin:NAME")
  std::string source_text;  ///< the YAML text it was read from (copied to sequences)
  /// Things that load but look wrong ("file:line: key: what"): a path through a wall, a box
  /// or a void, a ceiling above the next storey's floor. Front ends print them.
  std::vector<std::string> warnings;
};

/// Geometry constants of railings (the format fixes the style, not the dimensions).
struct RailingGeometry {
  static constexpr double kSolidThickness = 0.04;  ///< glass or panel
  static constexpr double kPostSpacing = 0.12;     ///< centre to centre, as the format says
  static constexpr double kPostWidth = 0.03;       ///< square posts
  static constexpr double kTopRailHeight = 0.05;   ///< the rail on top of the posts
};

}  // namespace tsgraphs::scene
