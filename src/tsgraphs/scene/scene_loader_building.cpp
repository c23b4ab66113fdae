#include <algorithm>
#include <filesystem>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "tsgraphs/core/limits.hpp"
#include "tsgraphs/core/yaml_map.hpp"
#include "tsgraphs/scene/scene_geometry.hpp"
#include "tsgraphs/scene/scene_loader_internal.hpp"

namespace tsgraphs::scene::scene_loader_internal {
namespace {

using limits::kMaxSceneExtent;

}  // namespace

void SceneParser::parse_levels() {
  const std::vector<YamlMap> maps = root_.maps("levels");
  if (maps.empty()) throw root_.error("levels", "a scene needs at least one level");
  for (const YamlMap& m : maps) {
    m.check_keys({"name", "elevation", "ceiling", "slab", "voids"});
    Level l;
    l.line = m.line();
    l.name = m.require<std::string>("name");
    for (const Level& other : scene_.levels) {
      if (other.name == l.name) throw m.error("name", "level '" + l.name + "' is defined twice");
    }
    l.elevation = m.get<double>("elevation", 0.0);
    require_within(m, "elevation", l.elevation, -kMaxSceneExtent, kMaxSceneExtent);
    l.ceiling = m.get<double>("ceiling", 3.0);
    require_positive(m, "ceiling", l.ceiling);
    if (!m.has("slab")) throw m.error_here("level '" + l.name + "' has no slab (the outline of its floor)");
    l.slab = simple_polygon(m, "slab");
    check_extent(m, "slab", l.slab);
    if (m.has("voids")) {
      const YAML::Node vs = m.raw("voids");
      if (!vs.IsSequence()) throw m.error("voids", "expected a list of polygons");
      for (std::size_t i = 0; i < vs.size(); ++i) {
        l.voids.push_back(simple_polygon(m, vs[i], m.key_path("voids") + "[" + std::to_string(i) + "]"));
      }
    }
    scene_.levels.push_back(std::move(l));
  }
}

void SceneParser::read_line(const YamlMap& m, const char* what, int* level, Vec2* from, Vec2* to) {
  *level = level_index(m, "level");
  *from = m.vec2("from");
  *to = m.vec2("to");
  check_extent(m, "from", {*from});
  check_extent(m, "to", {*to});
  if ((*to - *from).norm() < 1e-6)
    throw m.error(
        "to", std::string("zero-length ") + what + ": from and to are the same point " + fmt_point(*from));
}

void SceneParser::parse_wall(const YamlMap& m) {
  m.check_keys({"level", "from", "to", "thickness", "height", "openings"});
  Wall w;
  w.line = m.line();
  read_line(m, "wall", &w.level, &w.from, &w.to);
  const double length = (w.to - w.from).norm();
  w.thickness = m.get<double>("thickness", 0.2);
  w.height = m.get<double>("height", scene_.levels[w.level].ceiling);
  require_positive(m, "thickness", w.thickness);
  require_positive(m, "height", w.height);
  std::vector<std::pair<double, double>> spans;
  for (const YamlMap& om : m.maps("openings")) {
    om.check_keys({"at", "width", "height", "sill", "transmission"});
    Opening o;
    o.at = om.require<double>("at");
    o.width = om.require<double>("width");
    o.height = om.get<double>("height", 2.1);
    o.sill = om.get<double>("sill", 0.0);
    o.transmission = om.get<double>("transmission", 1.0);
    if (!(o.transmission >= 0.0 && o.transmission <= 1.0))
      throw om.error("transmission", "must lie in [0, 1]");
    require_positive(om, "width", o.width);
    require_positive(om, "height", o.height);
    require_non_negative(om, "sill", o.sill);
    if (o.width > length + 1e-9) {
      std::ostringstream s;
      s << "opening " << o.width << " m wide is wider than its wall (" << length << " m)";
      throw om.error("width", s.str());
    }
    if (o.at - 0.5 * o.width < -1e-9 || o.at + 0.5 * o.width > length + 1e-9) {
      std::ostringstream s;
      s << "opening spans " << o.at - 0.5 * o.width << " to " << o.at + 0.5 * o.width << " m along a wall of "
        << length << " m";
      throw om.error("at", s.str());
    }
    if (o.sill + o.height > w.height + 1e-9) {
      throw om.error("height", "sill + height exceeds the wall's height");
    }
    for (const auto& [lo, hi] : spans) {
      if (o.at - 0.5 * o.width < hi - 1e-9 && o.at + 0.5 * o.width > lo + 1e-9) {
        throw om.error("at", "opening overlaps another opening of the same wall");
      }
    }
    spans.emplace_back(o.at - 0.5 * o.width, o.at + 0.5 * o.width);
    w.openings.push_back(o);
  }
  std::sort(w.openings.begin(), w.openings.end(),
            [](const Opening& a, const Opening& b) { return a.at < b.at; });
  scene_.walls.push_back(std::move(w));
}

void SceneParser::parse_railing(const YamlMap& m) {
  m.check_keys({"level", "from", "to", "height", "style", "transmission"});
  Railing r;
  r.line = m.line();
  read_line(m, "railing", &r.level, &r.from, &r.to);
  r.height = m.get<double>("height", 1.0);
  require_positive(m, "height", r.height);
  const std::string style = m.get<std::string>("style", "solid");
  if (style == "solid")
    r.style = RailingStyle::kSolid;
  else if (style == "bars")
    r.style = RailingStyle::kBars;
  else if (style == "glass")
    r.style = RailingStyle::kGlass;
  else
    throw m.error("style", "unknown railing style '" + style + "' (solid, bars, glass)");
  if (m.has("transmission") && r.style != RailingStyle::kGlass)
    throw m.error("transmission", "only a glass railing lets rays through (style: glass)");
  r.transmission = m.get<double>("transmission", r.transmission);
  if (!(r.transmission >= 0.0 && r.transmission <= 1.0)) throw m.error("transmission", "must lie in [0, 1]");
  scene_.railings.push_back(r);
}

void SceneParser::parse_box(const YamlMap& m) {
  m.check_keys({"level", "min", "max", "yaw_deg", "label"});
  Box b;
  b.line = m.line();
  b.level = level_index(m, "level");
  b.min = vec3(m, "min");
  b.max = vec3(m, "max");
  check_extent(m, "min", {b.min.head<2>()});
  check_extent(m, "max", {b.max.head<2>()});
  require_within(m, "min", b.min.z(), -kMaxSceneExtent, kMaxSceneExtent);
  require_within(m, "max", b.max.z(), -kMaxSceneExtent, kMaxSceneExtent);
  if ((b.max - b.min).minCoeff() <= 0.0) throw m.error("max", "must exceed min on every axis");
  b.yaw_deg = m.get<double>("yaw_deg", 0.0);
  b.label = m.get<std::string>("label", "box");
  scene_.boxes.push_back(b);
}

void SceneParser::parse_voxel_map(const YamlMap& m) {
  m.check_keys({"file", "voxel_size", "level", "label", "offset", "yaw_deg"});
  VoxelMap v;
  v.line = m.line();
  const std::string file = m.require<std::string>("file");
  const std::filesystem::path p(file);
  v.file = p.is_absolute() ? p.string() : (std::filesystem::path(base_dir_) / p).lexically_normal().string();
  if (!std::filesystem::is_regular_file(v.file)) throw m.error("file", "no such file: " + v.file);
  v.voxel_size = m.require<double>("voxel_size");
  require_positive(m, "voxel_size", v.voxel_size);
  v.level = level_index(m, "level");
  const std::string label = m.get<std::string>("label", "auto");
  if (label == "wall")
    v.label = VoxelLabel::kWall;
  else if (label == "box")
    v.label = VoxelLabel::kBox;
  else if (label == "railing")
    v.label = VoxelLabel::kRailing;
  else if (label == "auto")
    v.label = VoxelLabel::kAuto;
  else
    throw m.error("label", "unknown voxel label '" + label + "' (wall, box, railing, auto)");
  v.offset = m.has("offset") ? vec3(m, "offset") : Eigen::Vector3d::Zero();
  check_extent(m, "offset", {v.offset.head<2>()});
  require_within(m, "offset", v.offset.z(), -kMaxSceneExtent, kMaxSceneExtent);
  v.yaw_deg = m.get<double>("yaw_deg", 0.0);
  scene_.voxel_maps.push_back(v);
}

void SceneParser::parse_ramp(const YamlMap& m) {
  m.check_keys({"from_level", "to_level", "polygon", "axis"});
  Ramp r;
  r.line = m.line();
  r.from_level = level_index(m, "from_level");
  r.to_level = level_index(m, "to_level");
  if (r.from_level == r.to_level) throw m.error("to_level", "a ramp joins two different levels");
  r.polygon = simple_polygon(m, "polygon");
  r.axis = m.vec2("axis");
  if (r.axis.norm() < 1e-9) throw m.error("axis", "must be a non-zero direction");
  r.axis.normalize();
  scene_.ramps.push_back(r);
}

void SceneParser::parse_room(const YamlMap& m) {
  m.check_keys({"name", "level", "polygon"});
  Room r;
  r.name = m.require<std::string>("name");
  r.level = level_index(m, "level");
  r.polygon = simple_polygon(m, "polygon");
  scene_.rooms.push_back(r);
}

void SceneParser::warn_about_storeys() {
  for (const Level& low : scene_.levels) {
    for (const Level& high : scene_.levels) {
      if (high.elevation <= low.elevation || low.elevation + low.ceiling <= high.elevation + 1e-9) continue;
      if (intersection_area(low.slab, high.slab) <= 0.0) continue;
      std::ostringstream msg;
      msg << "levels: the ceiling of " << low.name << " (z " << low.elevation + low.ceiling
          << ") is above the floor of " << high.name << " (z " << high.elevation << ")";
      warn(high.line, msg.str());
    }
  }
}

}  // namespace tsgraphs::scene::scene_loader_internal
