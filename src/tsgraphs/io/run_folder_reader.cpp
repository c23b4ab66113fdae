// A run folder's JSON files read: scene_graph.json, rooms_events.jsonl, run_info.json; every value
// checked and a bad one named by its key path.
#include "tsgraphs/io/run_folder.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <type_traits>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/core/text_file.hpp"
#include "tsgraphs/io/coordinate_limit.hpp"
#include "tsgraphs/io/run_folder_internal.hpp"

namespace tsgraphs::io {

namespace run_folder_internal {

namespace {

std::string quoted(const std::string& name) { return "'" + name + "'"; }

double finite(double x, const std::string& name) {
  if (!std::isfinite(x)) throw FieldError(quoted(name) + " must be finite");
  return x;
}

}  // namespace

std::string read_text(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw input_error(path, 0, "is a folder, not a file");
  return read_text_file(path, "cannot open (is this a run folder written by `tsgraphs run`?)");
}

std::string item(const std::string& parent, std::size_t i) { return parent + "[" + std::to_string(i) + "]"; }

double bounded_coordinate(double x, const std::string& name) {
  if (std::abs(finite(x, name)) > kMaxCoordinate) {
    char text[32];
    std::snprintf(text, sizeof(text), "%g", x);
    throw FieldError(quoted(name) + " is " + text + ": not a coordinate within 1e8 m");
  }
  return x;
}

}  // namespace run_folder_internal

using namespace run_folder_internal;

namespace {

using nlohmann::json;

// The line (from 1) of the first JSON number in `text` too large for a double, 0 for none.
// nlohmann::json reports such an overflow without its place.
int line_of_overflowing_number(const std::string& text) {
  int line = 1;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
    } else if (c == '"') {  // skip a string, escapes included
      for (++i; i < text.size() && text[i] != '"'; ++i) i += text[i] == '\\' ? 1 : 0;
    } else if (c == '-' || (c >= '0' && c <= '9')) {
      const char* start = text.c_str() + i;
      char* end = nullptr;
      const double v = std::strtod(start, &end);
      if (end == start) continue;
      if (!std::isfinite(v)) return line;
      i += static_cast<std::size_t>(end - start) - 1;
    }
  }
  return 0;
}

// The document in `text`; a syntax error or a number beyond a double names the line it is on.
json parse_json(const std::string& text, const std::string& path, int line = 0) {
  try {
    return json::parse(text);
  } catch (const json::parse_error& e) {
    if (line == 0) {
      line = 1;
      const std::size_t end = std::min<std::size_t>(e.byte > 0 ? e.byte - 1 : 0, text.size());
      for (std::size_t i = 0; i < end; ++i) line += text[i] == '\n' ? 1 : 0;
    }
    throw input_error(path, line, std::string("malformed JSON: ") + e.what());
  } catch (const json::out_of_range& e) {  // 406: a number such as 1e400
    if (line == 0) line = line_of_overflowing_number(text);
    const std::string what = e.what();
    const std::size_t quote = what.find('\'');
    throw input_error(path, line,
                      "number out of the range of a double" +
                          (quote == std::string::npos ? "" : ": " + what.substr(quote)));
  }
}

// ---- typed access to JSON values ----------------------------------------------------------

const json& object(const json& v, const std::string& name) {
  if (!v.is_object())
    throw FieldError(name.empty() ? "expected a JSON object" : quoted(name) + " must be an object");
  return v;
}

std::string child(const std::string& parent, const char* key) {
  return parent.empty() ? key : parent + "." + key;
}

const json& member(const json& obj, const char* key, const std::string& parent) {
  const auto it = obj.find(key);
  if (it == obj.end()) throw FieldError("missing key " + quoted(child(parent, key)));
  return *it;
}

const json* optional_member(const json& obj, const char* key) {
  const auto it = obj.find(key);
  return it == obj.end() ? nullptr : &*it;
}

const json& array(const json& v, const std::string& name) {
  if (!v.is_array()) throw FieldError(quoted(name) + " must be an array");
  return v;
}

double number(const json& v, const std::string& name) {
  if (!v.is_number()) throw FieldError(quoted(name) + " must be a number");
  return finite(v.get<double>(), name);
}

double coordinate(const json& v, const std::string& name) {
  return bounded_coordinate(number(v, name), name);
}

template <class Int>
Int integer(const json& v, const std::string& name) {
  if (!v.is_number_integer()) throw FieldError(quoted(name) + " must be an integer");
  if constexpr (std::is_unsigned_v<Int>) {
    if (v.is_number_unsigned()) {
      const std::uint64_t u = v.get<std::uint64_t>();
      if (u > std::numeric_limits<Int>::max()) throw FieldError(quoted(name) + " is out of range");
      return static_cast<Int>(u);
    }
    throw FieldError(quoted(name) + " must not be negative");
  } else {
    if (v.is_number_unsigned() &&
        v.get<std::uint64_t>() > static_cast<std::uint64_t>(std::numeric_limits<Int>::max()))
      throw FieldError(quoted(name) + " is out of range");
    const std::int64_t i = v.get<std::int64_t>();
    if (i < std::numeric_limits<Int>::min() || i > std::numeric_limits<Int>::max())
      throw FieldError(quoted(name) + " is out of range");
    return static_cast<Int>(i);
  }
}

std::string string(const json& v, const std::string& name) {
  if (!v.is_string()) throw FieldError(quoted(name) + " must be a string");
  return v.get<std::string>();
}

bool boolean(const json& v, const std::string& name) {
  if (!v.is_boolean()) throw FieldError(quoted(name) + " must be true or false");
  return v.get<bool>();
}

template <int N>
Eigen::Matrix<double, N, 1> vector_of(const json& v, const std::string& name) {
  static const char* const kShape[] = {"", "", "[x, y]", "[x, y, z]", "[x, y, z, w]"};
  if (!v.is_array() || v.size() != N) throw FieldError(quoted(name) + " must be " + kShape[N]);
  Eigen::Matrix<double, N, 1> out;
  for (int i = 0; i < N; ++i) {
    if (!v[i].is_number()) throw FieldError(quoted(name) + " must be " + kShape[N]);
    out[i] = coordinate(v[i], item(name, static_cast<std::size_t>(i)));
  }
  return out;
}

std::vector<int> ints(const json& v, const std::string& name) {
  std::vector<int> out;
  for (std::size_t i = 0; i < array(v, name).size(); ++i) out.push_back(integer<int>(v[i], item(name, i)));
  return out;
}

// The fields of obj.key, each named with its path.
double number_at(const json& obj, const char* key, const std::string& parent) {
  return number(member(obj, key, parent), child(parent, key));
}
template <class Int>
Int integer_at(const json& obj, const char* key, const std::string& parent) {
  return integer<Int>(member(obj, key, parent), child(parent, key));
}
std::string string_at(const json& obj, const char* key, const std::string& parent) {
  return string(member(obj, key, parent), child(parent, key));
}
template <int N>
Eigen::Matrix<double, N, 1> vector_at(const json& obj, const char* key, const std::string& parent) {
  return vector_of<N>(member(obj, key, parent), child(parent, key));
}

// Each element of the array obj.key (absent: none when `required` is false) as an object.
template <class F>
void for_each_object(const json& obj, const char* key, const std::string& parent, bool required, F&& f) {
  const json* list = required ? &member(obj, key, parent) : optional_member(obj, key);
  if (list == nullptr) return;
  const std::string name = child(parent, key);
  array(*list, name);
  for (std::size_t i = 0; i < list->size(); ++i) f(object((*list)[i], item(name, i)), item(name, i));
}

PoseRecord pose_at(const json& obj, const char* key, const std::string& parent) {
  const std::string name = child(parent, key);
  const json& p = object(member(obj, key, parent), name);
  PoseRecord out;
  out.t = vector_at<3>(p, "t", name);
  const Eigen::Vector4d q = vector_at<4>(p, "q", name);
  out.q = Eigen::Quaterniond(q[3], q[0], q[1], q[2]);
  if (out.q.norm() == 0.0) throw FieldError(quoted(child(name, "q")) + " must not be zero");
  return out;
}

OrientedRect rect_at(const json& obj, const char* key, const std::string& parent) {
  const std::string name = child(parent, key);
  const json& r = object(member(obj, key, parent), name);
  OrientedRect rect;
  rect.center = vector_at<2>(r, "center", name);
  rect.size = vector_at<2>(r, "size", name);
  if (rect.size.x() < 0.0 || rect.size.y() < 0.0)
    throw FieldError(quoted(child(name, "size")) + " must not be negative");
  rect.yaw = number_at(r, "yaw", name);
  return rect;
}

/// An optional footprint polygon: [[x, y], ...] with at least 3 vertices.
Polygon2 polygon_at(const json& obj, const char* key, const std::string& parent) {
  const json* v = optional_member(obj, key);
  if (v == nullptr) return {};
  const std::string name = child(parent, key);
  Polygon2 out;
  for (std::size_t i = 0; i < array(*v, name).size(); ++i)
    out.push_back(vector_of<2>((*v)[i], item(name, i)));
  if (out.size() < 3) throw FieldError(quoted(name) + " must have at least 3 vertices");
  return out;
}

std::string room_kind_at(const json& obj, const std::string& parent) {
  const std::string kind = string_at(obj, "kind", parent);
  if (kind != "room" && kind != "corridor")
    throw FieldError(quoted(child(parent, "kind")) + " must be \"room\" or \"corridor\"");
  return kind;
}

// ---- scene graph, parts -------------------------------------------------------------------

SceneGraph::Plane plane_of(const json& p, const std::string& name) {
  SceneGraph::Plane out;
  out.id = integer_at<int>(p, "id", name);
  out.kind = string_at(p, "kind", name);
  out.n = vector_at<3>(p, "n", name);
  out.d = coordinate(member(p, "d", name), child(name, "d"));
  out.keyframes = ints(member(p, "keyframes", name), child(name, "keyframes"));
  if (const json* v = optional_member(p, "num_points"))
    out.num_points = integer<std::size_t>(*v, child(name, "num_points"));
  if (const json* v = optional_member(p, "centroid"))
    out.centroid = vector_of<3>(*v, child(name, "centroid"));
  if (const json* v = optional_member(p, "segment")) {
    const std::string seg = child(name, "segment");
    if (!v->is_array() || v->size() != 2) throw FieldError(quoted(seg) + " must be [[x, y], [x, y]]");
    out.segment =
        std::array<Vec2, 2>{vector_of<2>((*v)[0], item(seg, 0)), vector_of<2>((*v)[1], item(seg, 1))};
  }
  if (const json* v = optional_member(p, "z_range")) {
    const Vec2 z = vector_of<2>(*v, child(name, "z_range"));
    out.z_range = std::array<double, 2>{z.x(), z.y()};
  }
  return out;
}

SceneGraph::TraversableNode node_of(const json& n, const std::string& name) {
  SceneGraph::TraversableNode out;
  out.id = integer_at<int>(n, "id", name);
  out.position = vector_at<3>(n, "position", name);
  out.normal = vector_at<3>(n, "normal", name);
  out.probability = number_at(n, "probability", name);
  if (const json* v = optional_member(n, "observations"))
    out.observations = integer<int>(*v, child(name, "observations"));
  if (const json* v = optional_member(n, "anchor_keyframe"))
    out.anchor_keyframe = integer<int>(*v, child(name, "anchor_keyframe"));
  if (const json* v = optional_member(n, "keyframes")) out.keyframes = ints(*v, child(name, "keyframes"));
  return out;
}

SceneGraph::Room room_of(const json& r, const std::string& name) {
  SceneGraph::Room out;
  out.id = integer_at<int>(r, "id", name);
  out.kind = room_kind_at(r, name);
  out.level = integer_at<int>(r, "level", name);
  out.rect = rect_at(r, "rect", name);
  out.polygon = polygon_at(r, "polygon", name);
  if (const json* v = optional_member(r, "walls")) out.walls = ints(*v, child(name, "walls"));
  if (const json* v = optional_member(r, "extractions"))
    out.extractions = integer<int>(*v, child(name, "extractions"));
  if (const json* v = optional_member(r, "node"); v != nullptr && !v->is_null())
    out.node = integer<int>(*v, child(name, "node"));
  if (const json* v = optional_member(r, "free_space")) {
    const std::string space = child(name, "free_space");
    for (std::size_t i = 0; i < array(*v, space).size(); ++i)
      out.free_space.push_back(vector_of<3>((*v)[i], item(space, i)));
  }
  return out;
}

void add_edge(const json& e, const std::string& name, SceneGraph* g) {
  const std::string type = string_at(e, "type", name);
  if (type == "odometry") {
    g->odometry_edges.push_back(
        {integer_at<int>(e, "from", name), integer_at<int>(e, "to", name), pose_at(e, "measurement", name)});
  } else if (type == "loop") {
    g->loop_edges.push_back({integer_at<int>(e, "from", name), integer_at<int>(e, "to", name),
                             number_at(e, "fitness", name), pose_at(e, "measurement", name),
                             optional_member(e, "folded") ? integer_at<int>(e, "folded", name) : 0});
  } else if (type == "keyframe_plane") {
    g->keyframe_plane_edges.push_back({integer_at<int>(e, "keyframe", name),
                                       integer_at<int>(e, "plane", name),
                                       vector_at<4>(e, "measurement", name)});
  } else if (type == "room_planes") {
    g->room_planes_edges.push_back({integer_at<int>(e, "room", name), room_kind_at(e, name),
                                    ints(member(e, "planes", name), child(name, "planes")),
                                    vector_at<2>(e, "cluster_center", name)});
  } else if (type == "floor_room") {
    g->floor_room_edges.push_back({integer_at<int>(e, "floor", name), integer_at<int>(e, "room", name)});
  }
  // Other types: a newer writer's; skipped.
}

}  // namespace

// ---- scene_graph.json ---------------------------------------------------------------------

SceneGraph read_scene_graph(const std::string& path) {
  const json doc = parse_json(read_text(path), path);
  SceneGraph g;
  try {
    object(doc, "");
    if (const json* f = optional_member(doc, "format"); f != nullptr && *f != "tsgraphs-scene-graph")
      throw FieldError("'format' is not \"tsgraphs-scene-graph\"");
    if (const json* f = optional_member(doc, "frame")) g.frame = string(*f, "frame");
    for_each_object(doc, "keyframes", "", true, [&](const json& k, const std::string& name) {
      SceneGraph::Keyframe kf;
      kf.id = integer_at<int>(k, "id", name);
      kf.scan_index = integer_at<std::size_t>(k, "scan_index", name);
      kf.stamp = number_at(k, "stamp", name);
      kf.accum_distance = number_at(k, "accum_distance", name);
      kf.pose = pose_at(k, "pose", name);
      kf.odom = pose_at(k, "odom", name);
      if (optional_member(k, "anchor")) kf.anchor = integer_at<int>(k, "anchor", name);
      g.keyframes.push_back(kf);
    });
    for_each_object(doc, "planes", "", true,
                    [&](const json& p, const std::string& name) { g.planes.push_back(plane_of(p, name)); });
    for_each_object(doc, "traversable_nodes", "", false, [&](const json& n, const std::string& name) {
      g.traversable_nodes.push_back(node_of(n, name));
    });
    for_each_object(doc, "rooms", "", false,
                    [&](const json& r, const std::string& name) { g.rooms.push_back(room_of(r, name)); });
    for_each_object(doc, "room_nodes", "", false, [&](const json& r, const std::string& name) {
      g.room_nodes.push_back({integer_at<int>(r, "id", name), room_kind_at(r, name),
                              integer_at<int>(r, "level", name), vector_at<2>(r, "center", name)});
    });
    for_each_object(doc, "floors", "", false, [&](const json& f, const std::string& name) {
      g.floors.push_back({integer_at<int>(f, "id", name), integer_at<int>(f, "level", name),
                          vector_at<2>(f, "center", name)});
    });
    if (const json* levels = optional_member(doc, "levels")) {
      for (std::size_t i = 0; i < array(*levels, "levels").size(); ++i)
        g.levels.push_back(coordinate((*levels)[i], item("levels", i)));
    }
    for_each_object(doc, "edges", "", true,
                    [&](const json& e, const std::string& name) { add_edge(e, name, &g); });
    for_each_object(doc, "loop_closures", "", false, [&](const json& l, const std::string& name) {
      g.loop_closures.push_back({integer_at<int>(l, "from", name), integer_at<int>(l, "to", name),
                                 number_at(l, "fitness", name), pose_at(l, "measurement", name),
                                 string_at(l, "proposer", name)});
    });
  } catch (const FieldError& e) {
    throw input_error(path, 0, e.what());
  }
  return g;
}

// ---- rooms_events.jsonl -------------------------------------------------------------------

std::vector<RoomEvent> read_room_events(const std::string& path) {
  std::istringstream in(read_text(path));
  std::vector<RoomEvent> events;
  std::string text;
  int line_no = 0;
  while (std::getline(in, text)) {
    ++line_no;
    if (text.find_first_not_of(" \t\r") == std::string::npos) continue;
    const json j = parse_json(text, path, line_no);
    try {
      object(j, "");
      RoomEvent e;
      e.t = number_at(j, "t", "");
      e.lap = integer_at<int>(j, "lap", "");
      if (e.lap < 1) throw FieldError("'lap' counts from 1");
      e.room_id = integer_at<int>(j, "room_id", "");
      e.is_new = boolean(member(j, "new", ""), "new");
      e.level = integer_at<int>(j, "level", "");
      e.center = vector_at<2>(j, "center", "");
      e.rect = rect_at(j, "rect", "");
      e.polygon = polygon_at(j, "polygon", "");
      e.walls = ints(member(j, "walls", ""), "walls");
      e.kind = room_kind_at(j, "");
      events.push_back(std::move(e));
    } catch (const FieldError& err) {
      throw input_error(path, line_no, err.what());
    }
  }
  return events;
}

// ---- run_info.json ------------------------------------------------------------------------

RunSummary read_run_summary(const std::string& path) {
  const json doc = parse_json(read_text(path), path);
  RunSummary s;
  try {
    object(doc, "");
    s.sequence = string_at(doc, "sequence", "");
    s.num_scans = integer_at<std::size_t>(doc, "num_scans", "");
    s.num_skipped = integer_at<std::size_t>(doc, "num_skipped", "");
    s.odometry = string_at(doc, "odometry", "");
    s.num_keyframes = integer_at<std::size_t>(doc, "num_keyframes", "");
    s.num_planes = integer_at<std::size_t>(doc, "num_planes", "");
    s.num_traversable_nodes = integer_at<std::size_t>(doc, "num_traversable_nodes", "");
    s.num_rooms = integer_at<std::size_t>(doc, "num_rooms", "");
    s.num_room_events = integer_at<std::size_t>(doc, "num_room_events", "");
    s.num_loops = integer_at<std::size_t>(doc, "num_loops", "");
    s.num_optimizations = integer_at<std::size_t>(doc, "num_optimizations", "");
    s.t_pgo_s = number_at(doc, "t_pgo_s", "");
    s.sequence_duration_s = number_at(doc, "sequence_duration_s", "");
    s.wall_time_s = number_at(doc, "wall_time_s", "");
    s.rtf = number_at(doc, "rtf", "");
    s.peak_rss_mb = number_at(doc, "peak_rss_mb", "");
    if (doc.contains("platform")) {
      const json& j = doc.at("platform");
      object(j, "platform");
      RunPlatform p;
      p.sensor_height = number_at(j, "sensor_height", "platform");
      p.sensor_height_source = string_at(j, "sensor_height_source", "platform");
      p.tilt_deg = number_at(j, "tilt_deg", "platform");
      p.scans_measured = integer_at<std::size_t>(j, "scans_measured", "platform");
      p.floors_found = integer_at<std::size_t>(j, "floors_found", "platform");
      p.height_spread = number_at(j, "height_spread", "platform");
      p.rings = integer_at<int>(j, "rings", "platform");
      p.ring_spacing_deg = number_at(j, "ring_spacing_deg", "platform");
      p.lowest_ring_deg = number_at(j, "lowest_ring_deg", "platform");
      p.preset = string_at(j, "preset", "platform");
      p.preset_source = string_at(j, "preset_source", "platform");
      p.seed_radius = number_at(j, "seed_radius", "platform");
      p.seed_radius_source = string_at(j, "seed_radius_source", "platform");
      s.platform = p;
    }
    if (doc.contains("warnings")) {
      if (!doc.at("warnings").is_array()) throw FieldError("warnings: expected a list of strings");
      for (const json& w : doc.at("warnings")) {
        if (!w.is_string()) throw FieldError("warnings: expected a list of strings");
        s.warnings.push_back(w.get<std::string>());
      }
    }
  } catch (const FieldError& e) {
    throw input_error(path, 0, e.what());
  }
  return s;
}

}  // namespace tsgraphs::io
