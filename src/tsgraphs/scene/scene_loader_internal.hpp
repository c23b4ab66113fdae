#pragma once
/// The scene loader's parser, shared by its files (scene_loader.cpp: the root, the checks every
/// part uses and the public functions; scene_loader_sensor.cpp: sensor, platform, odometry;
/// scene_loader_building.cpp: levels, walls, railings, boxes, voxel maps, ramps, rooms;
/// scene_loader_path.cpp: the trajectory, the people and the warnings about the path).
#include <limits>
#include <string>
#include <utility>

#include "tsgraphs/core/rect.hpp"
#include "tsgraphs/core/yaml_map.hpp"
#include "tsgraphs/scene/scene.hpp"

namespace tsgraphs::scene::scene_loader_internal {

/// "[x, y]", as the messages name a point.
std::string fmt_point(const Vec2& p);

/// Reads one scene file's root map into a Scene; every problem an InputError naming the file,
/// the line and the key.
class SceneParser {
 public:
  SceneParser(const YamlMap& root, std::string base_dir) : root_(root), base_dir_(std::move(base_dir)) {}

  Scene parse();

 private:
  // Checks every part uses (scene_loader.cpp).
  // Grows the scene's box by `points` (of `key` in `m`) and refuses a coordinate or a box
  // beyond the bounds of a building.
  void check_extent(const YamlMap& m, const std::string& key, const Polygon2& points);
  static void require_positive(const YamlMap& m, const std::string& key, double v);
  static void require_non_negative(const YamlMap& m, const std::string& key, double v);
  static void require_within(const YamlMap& m, const std::string& key, double v, double lo, double hi);
  int level_index(const YamlMap& m, const std::string& key) const;
  std::string known_levels() const;
  // Reads a polygon and rejects repeated vertices, self-intersections and zero area.
  Polygon2 simple_polygon(const YamlMap& m, const YAML::Node& node, const std::string& where) const;
  Polygon2 simple_polygon(const YamlMap& m, const std::string& key) const;
  Eigen::Vector3d vec3(const YamlMap& m, const std::string& key) const;
  void warn(int line, const std::string& what);

  // Sensor, platform and odometry (scene_loader_sensor.cpp).
  void parse_sensor(const YamlMap& m);
  void parse_platform(const YamlMap& m);
  void parse_odometry(const YamlMap& m);
  // A sensor at or above the ceiling of a level the path walks sees nothing of that level.
  void check_mount_height() const;

  // The building (scene_loader_building.cpp).
  void parse_levels();
  /// A wall's or railing's level and two distinct ends within the extent limit.
  void read_line(const YamlMap& m, const char* what, int* level, Vec2* from, Vec2* to);
  void parse_wall(const YamlMap& m);
  void parse_railing(const YamlMap& m);
  void parse_box(const YamlMap& m);
  void parse_voxel_map(const YamlMap& m);
  void parse_ramp(const YamlMap& m);
  void parse_room(const YamlMap& m);
  // A ceiling above the floor of the storey on top of it (where their slabs overlap).
  void warn_about_storeys();

  // The path and the people on it (scene_loader_path.cpp).
  void parse_trajectory(const YamlMap& m);
  void check_waypoint(const Waypoint& w, const std::string& where) const;
  // The number of scans the path makes, against limits::kMaxSequenceScans: a slow speed or many
  // laps of a long path could otherwise fill the disk.
  void check_sequence_length() const;
  void parse_person(const YamlMap& m);
  // Straight legs of the path that pass through a wall (outside a door), a box standing on
  // the floor or a void: the simulator would carry the sensor through them.
  void warn_about_path();
  // True when the void is the opening of a ramp joining `level` (the ramp is walked over it).
  bool void_holds_ramp(int level, const Polygon2& void_polygon) const;
  static bool segment_meets(const Vec2& a, const Vec2& b, const OrientedRect& r);

  const YamlMap& root_;
  std::string base_dir_;
  Scene scene_;
  Vec2 lo_ = Vec2::Constant(std::numeric_limits<double>::infinity());  // the slabs' and walls' box so far
  Vec2 hi_ = -Vec2::Constant(std::numeric_limits<double>::infinity());
};

}  // namespace tsgraphs::scene::scene_loader_internal
