#include "tsgraphs/io/run_folder.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <type_traits>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/core/printable.hpp"
#include "tsgraphs/core/text_file.hpp"
#include "tsgraphs/io/coordinate_limit.hpp"

namespace tsgraphs::io {
namespace {

using nlohmann::json;

// What is wrong with one value, named by its key path ('rooms[2].rect.size'); the caller adds
// the file and, for line-based files, the line.
struct FieldError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

std::string quoted(const std::string& name) { return "'" + name + "'"; }

std::string read_text(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw input_error(path, 0, "is a folder, not a file");
  return read_text_file(path, "cannot open (is this a run folder written by `tsgraphs run`?)");
}

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
std::string item(const std::string& parent, std::size_t i) { return parent + "[" + std::to_string(i) + "]"; }

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

double finite(double x, const std::string& name) {
  if (!std::isfinite(x)) throw FieldError(quoted(name) + " must be finite");
  return x;
}

double number(const json& v, const std::string& name) {
  if (!v.is_number()) throw FieldError(quoted(name) + " must be a number");
  return finite(v.get<double>(), name);
}

// A value in metres of the map (or a unit vector's or quaternion's component): finite, bounded.
double bounded_coordinate(double x, const std::string& name) {
  if (std::abs(finite(x, name)) > kMaxCoordinate) {
    char text[32];
    std::snprintf(text, sizeof(text), "%g", x);
    throw FieldError(quoted(name) + " is " + text + ": not a coordinate within 1e8 m");
  }
  return x;
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

// ---- JSON values written ------------------------------------------------------------------

json xy(const Vec2& v) { return {v.x(), v.y()}; }
json xyz(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }
json pose_json(const PoseRecord& p) { return {{"t", xyz(p.t)}, {"q", {p.q.x(), p.q.y(), p.q.z(), p.q.w()}}}; }
json rect_json(const OrientedRect& r) {
  return {{"center", xy(r.center)}, {"size", xy(r.size)}, {"yaw", r.yaw}};
}
json polygon_json(const Polygon2& p) {
  json out = json::array();
  for (const Vec2& v : p) out.push_back(xy(v));
  return out;
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

// ---- timings.csv --------------------------------------------------------------------------

constexpr const char* kTimingsHeader =
    "kind,index,stamp,keyframe,num_points,prefilter_ms,walls_ms,loop_ms,frontend_ms,"
    "optimization_s,full,n_variables,n_factors,iterations,reason,"
    "ground_ms,ground_nodes,ground_tp,ground_fp,ground_fn,rooms_ms";
// The most points one scan can hold (a 128-beam sensor gives a few million): bounds the ground
// counts of timings.csv.
constexpr long kMaxScanPoints = 1'000'000'000;
// Columns added later: read when present (older run folders lack them).
constexpr const char* kActiveKeyframes = "active_keyframes";

// printf into the end of `out` (rows may be longer than any fixed buffer: a long warning).
void append(std::string* out, const char* format, ...) __attribute__((format(printf, 2, 3)));
void append(std::string* out, const char* format, ...) {
  va_list args, copy;
  va_start(args, format);
  va_copy(copy, args);
  const int n = std::vsnprintf(nullptr, 0, format, copy);
  va_end(copy);
  const std::size_t at = out->size();
  out->resize(at + static_cast<std::size_t>(n) + 1);
  std::vsnprintf(out->data() + at, static_cast<std::size_t>(n) + 1, format, args);
  out->resize(at + static_cast<std::size_t>(n));
  va_end(args);
}

// A CSV field: quoted when not empty (the warnings are free text), quotes doubled.
std::string quote_csv(const std::string& text) {
  if (text.empty()) return text;
  std::string out = "\"";
  for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

// The fields of one CSV line; a field in double quotes may hold commas and doubled quotes.
std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> fields(1);
  bool in_quotes = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (in_quotes) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        fields.back() += '"';
        ++i;
      } else if (c == '"') {
        in_quotes = false;
      } else {
        fields.back() += c;
      }
    } else if (c == '"') {
      in_quotes = true;
    } else if (c == ',') {
      fields.emplace_back();
    } else {
      fields.back() += c;
    }
  }
  if (in_quotes) throw FieldError("unterminated quoted field");
  return fields;
}

template <class T>
bool parse_whole(const std::string& field, T* v) {
  const char* end = field.data() + field.size();
  const auto r = std::from_chars(field.data(), end, *v);
  return r.ec == std::errc() && r.ptr == end;
}

}  // namespace

// ---- scene_graph.json ---------------------------------------------------------------------

PoseRecord PoseRecord::of(const Pose3& pose) {
  PoseRecord p;
  p.t = pose.translation();
  p.q = Eigen::Quaterniond(pose.linear());
  return p;
}

Pose3 PoseRecord::pose() const {
  Pose3 T = Pose3::Identity();
  T.linear() = q.normalized().toRotationMatrix();
  T.translation() = t;
  return T;
}

std::string format_scene_graph(const SceneGraph& g) {
  json keyframes = json::array();
  for (const SceneGraph::Keyframe& k : g.keyframes) {
    keyframes.push_back({{"id", k.id},
                         {"scan_index", k.scan_index},
                         {"stamp", k.stamp},
                         {"accum_distance", k.accum_distance},
                         {"pose", pose_json(k.pose)},
                         {"odom", pose_json(k.odom)}});
    if (k.anchor >= 0) keyframes.back()["anchor"] = k.anchor;
  }
  json planes = json::array();
  for (const SceneGraph::Plane& p : g.planes) {
    json plane = {{"id", p.id}, {"kind", p.kind}, {"n", xyz(p.n)}, {"d", p.d}, {"keyframes", p.keyframes}};
    if (p.num_points) plane["num_points"] = *p.num_points;
    if (p.centroid) plane["centroid"] = xyz(*p.centroid);
    if (p.segment) plane["segment"] = {xy((*p.segment)[0]), xy((*p.segment)[1])};
    if (p.z_range) plane["z_range"] = {(*p.z_range)[0], (*p.z_range)[1]};
    planes.push_back(plane);
  }
  json edges = json::array();
  for (const SceneGraph::OdometryEdge& e : g.odometry_edges)
    edges.push_back(
        {{"type", "odometry"}, {"from", e.from}, {"to", e.to}, {"measurement", pose_json(e.measurement)}});
  for (const SceneGraph::LoopEdge& e : g.loop_edges) {
    edges.push_back({{"type", "loop"},
                     {"from", e.from},
                     {"to", e.to},
                     {"fitness", e.fitness},
                     {"measurement", pose_json(e.measurement)}});
    if (e.folded > 0) edges.back()["folded"] = e.folded;
  }
  for (const SceneGraph::KeyframePlaneEdge& e : g.keyframe_plane_edges)
    edges.push_back(
        {{"type", "keyframe_plane"},
         {"keyframe", e.keyframe},
         {"plane", e.plane},
         {"measurement", {e.measurement[0], e.measurement[1], e.measurement[2], e.measurement[3]}}});
  for (const SceneGraph::RoomPlanesEdge& e : g.room_planes_edges)
    edges.push_back({{"type", "room_planes"},
                     {"room", e.room},
                     {"kind", e.kind},
                     {"planes", e.planes},
                     {"cluster_center", xy(e.cluster_center)}});
  for (const SceneGraph::FloorRoomEdge& e : g.floor_room_edges)
    edges.push_back({{"type", "floor_room"}, {"floor", e.floor}, {"room", e.room}});
  json nodes = json::array();
  for (const SceneGraph::TraversableNode& n : g.traversable_nodes) {
    nodes.push_back({{"id", n.id},
                     {"position", xyz(n.position)},
                     {"normal", xyz(n.normal)},
                     {"probability", n.probability},
                     {"observations", n.observations},
                     {"anchor_keyframe", n.anchor_keyframe},
                     {"keyframes", n.keyframes}});
  }
  json room_nodes = json::array();
  for (const SceneGraph::RoomNode& r : g.room_nodes)
    room_nodes.push_back({{"id", r.id}, {"kind", r.kind}, {"level", r.level}, {"center", xy(r.center)}});
  json floors = json::array();
  for (const SceneGraph::Floor& f : g.floors)
    floors.push_back({{"id", f.id}, {"level", f.level}, {"center", xy(f.center)}});
  json rooms = json::array();
  for (const SceneGraph::Room& r : g.rooms) {
    json space = json::array();
    for (const Eigen::Vector3d& p : r.free_space) space.push_back(xyz(p));
    json room = {{"id", r.id},
                 {"kind", r.kind},
                 {"level", r.level},
                 {"rect", rect_json(r.rect)},
                 {"walls", r.walls},
                 {"extractions", r.extractions},
                 {"node", r.node ? json(*r.node) : json(nullptr)},
                 {"free_space", space}};
    if (!r.polygon.empty()) room["polygon"] = polygon_json(r.polygon);
    rooms.push_back(std::move(room));
  }
  json loop_closures = json::array();
  for (const SceneGraph::LoopClosure& l : g.loop_closures)
    loop_closures.push_back({{"from", l.from},
                             {"to", l.to},
                             {"fitness", l.fitness},
                             {"measurement", pose_json(l.measurement)},
                             {"proposer", l.proposer}});
  // nlohmann::json keeps keys sorted: the file's layout since version 1.
  const json doc = {{"format", "tsgraphs-scene-graph"},
                    {"version", 1},
                    {"frame", g.frame},
                    {"keyframes", keyframes},
                    {"planes", planes},
                    {"traversable_nodes", nodes},
                    {"rooms", rooms},
                    {"room_nodes", room_nodes},
                    {"floors", floors},
                    {"levels", g.levels},
                    {"edges", edges},
                    {"loop_closures", loop_closures}};
  return doc.dump(1) + "\n";
}

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

std::string format_room_event(const RoomEvent& e) {
  json j;  // sorted keys
  j["t"] = e.t;
  j["lap"] = e.lap;
  j["room_id"] = e.room_id;
  j["new"] = e.is_new;
  j["level"] = e.level;
  j["center"] = xy(e.center);
  j["rect"] = rect_json(e.rect);
  if (!e.polygon.empty()) j["polygon"] = polygon_json(e.polygon);
  j["walls"] = e.walls;
  j["kind"] = e.kind;
  return j.dump();
}

std::string format_room_events(const std::vector<RoomEvent>& events) {
  std::string out;
  for (const RoomEvent& e : events) out += format_room_event(e) + "\n";
  return out;
}

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

// ---- timings.csv --------------------------------------------------------------------------

std::string format_timings(const Timings& t) {
  std::string out = std::string(kTimingsHeader) + "," + kActiveKeyframes + "\n";
  for (const ScanTiming& s : t.scans) {
    append(&out, "scan,%zu,%.6f,%d,%zu,%.3f,%.3f,%.3f,%.3f,,,,,,%s,%.3f,%zu,%ld,%ld,%ld,%.3f,\n", s.index,
           s.stamp, s.keyframe, s.num_points, s.prefilter_ms, s.walls_ms, s.loop_ms, s.frontend_ms,
           quote_csv(s.warning).c_str(), s.ground_ms, s.ground_nodes, s.ground_tp, s.ground_fp, s.ground_fn,
           s.rooms_ms);
  }
  for (const OptimizationTiming& o : t.optimizations) {
    append(&out, "optimization,%zu,%.6f,%d,,,,,,%.6f,%d,%d,%d,%d,%s,,,,,,,%d\n", o.index, o.stamp, o.keyframe,
           o.seconds, o.full ? 1 : 0, o.n_variables, o.n_factors, o.iterations, o.reason.c_str(),
           o.active_keyframes);
  }
  return out;
}

Timings read_timings(const std::string& path) {
  std::istringstream in(read_text(path));
  std::string line;
  if (!std::getline(in, line)) throw input_error(path, 1, "empty: expected the header line");
  if (!line.empty() && line.back() == '\r') line.pop_back();
  std::vector<std::string> header;
  try {
    header = split_csv(line);
  } catch (const FieldError& e) {
    throw input_error(path, 1, e.what());
  }
  if (header[0] != "kind") throw input_error(path, 1, "header must start with 'kind'");
  // Column of each name; every one the writer writes must be there.
  std::vector<std::size_t> col;
  for (const std::string& name : split_csv(kTimingsHeader)) {
    const auto it = std::find(header.begin(), header.end(), name);
    if (it == header.end()) throw input_error(path, 1, "header has no column '" + name + "'");
    col.push_back(static_cast<std::size_t>(it - header.begin()));
  }
  const auto active_at = std::find(header.begin(), header.end(), kActiveKeyframes);
  const std::size_t active_col =
      active_at == header.end() ? header.size() : static_cast<std::size_t>(active_at - header.begin());
  const std::vector<std::string> names = split_csv(kTimingsHeader);
  enum Column {
    kIndex = 1,
    kStamp,
    kKeyframe,
    kNumPoints,
    kPrefilter,
    kWalls,
    kLoop,
    kFrontend,
    kSeconds,
    kFull,
    kVariables,
    kFactors,
    kIterations,
    kReason,
    kGroundMs,
    kGroundNodes,
    kTp,
    kFp,
    kFn,
    kRoomsMs
  };
  Timings t;
  int line_no = 1;
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    try {
      const std::vector<std::string> cols = split_csv(line);
      const std::string& kind = cols[0];
      auto field = [&](Column c) -> const std::string& {
        static const std::string kNone;
        return col[c] < cols.size() ? cols[col[c]] : kNone;
      };
      auto bad = [&](Column c) {
        return FieldError("malformed " + names[c] +
                          (kind == "scan" ? " in a scan row" : " in an optimization row"));
      };
      auto real = [&](Column c) {
        double v = 0.0;
        if (!parse_whole(field(c), &v) || !std::isfinite(v)) throw bad(c);
        return v;
      };
      auto whole = [&](Column c, auto* v) {
        if (!parse_whole(field(c), v)) throw bad(c);
      };
      if (kind == "scan") {
        ScanTiming s;
        whole(kIndex, &s.index);
        s.stamp = real(kStamp);
        whole(kKeyframe, &s.keyframe);
        whole(kNumPoints, &s.num_points);
        s.prefilter_ms = real(kPrefilter);
        s.walls_ms = real(kWalls);
        s.loop_ms = real(kLoop);
        s.frontend_ms = real(kFrontend);
        s.warning = field(kReason);
        s.ground_ms = real(kGroundMs);
        whole(kGroundNodes, &s.ground_nodes);
        whole(kTp, &s.ground_tp);
        whole(kFp, &s.ground_fp);
        whole(kFn, &s.ground_fn);
        // eval sums these over the scans: a corrupt count must not overflow the sum.
        for (const auto& [c, v] : {std::pair{kTp, s.ground_tp}, {kFp, s.ground_fp}, {kFn, s.ground_fn}}) {
          if (v < -1 || v > kMaxScanPoints)
            throw FieldError(names[c] +
                             " in a scan row must be -1 (no labels) or a count of a scan's points");
        }
        s.rooms_ms = real(kRoomsMs);
        t.scans.push_back(std::move(s));
      } else if (kind == "optimization") {
        OptimizationTiming o;
        whole(kIndex, &o.index);
        o.stamp = real(kStamp);
        whole(kKeyframe, &o.keyframe);
        o.seconds = real(kSeconds);
        int full = 0;
        whole(kFull, &full);
        if (full != 0 && full != 1) throw FieldError("full must be 0 or 1");
        o.full = full == 1;
        whole(kVariables, &o.n_variables);
        whole(kFactors, &o.n_factors);
        whole(kIterations, &o.iterations);
        o.reason = field(kReason);
        if (active_col < cols.size() && !parse_whole(cols[active_col], &o.active_keyframes))
          throw FieldError(std::string("malformed ") + kActiveKeyframes + " in an optimization row");
        t.optimizations.push_back(std::move(o));
      } else {
        throw FieldError("expected a scan or optimization row, got '" + kind + "'");
      }
    } catch (const FieldError& e) {
      throw input_error(path, line_no, e.what());
    }
  }
  return t;
}

// ---- run_info.json ------------------------------------------------------------------------

std::string format_run_summary(const RunSummary& s) {
  const json doc = {{"sequence", s.sequence},
                    {"num_scans", s.num_scans},
                    {"num_skipped", s.num_skipped},
                    {"odometry", s.odometry},
                    {"num_keyframes", s.num_keyframes},
                    {"num_planes", s.num_planes},
                    {"num_traversable_nodes", s.num_traversable_nodes},
                    {"num_rooms", s.num_rooms},
                    {"num_room_events", s.num_room_events},
                    {"num_loops", s.num_loops},
                    {"num_optimizations", s.num_optimizations},
                    {"t_pgo_s", s.t_pgo_s},
                    {"sequence_duration_s", s.sequence_duration_s},
                    {"wall_time_s", s.wall_time_s},
                    {"rtf", s.rtf},
                    {"peak_rss_mb", s.peak_rss_mb}};
  json out = doc;
  if (s.platform) {
    const RunPlatform& p = *s.platform;
    out["platform"] = {{"sensor_height", p.sensor_height},
                       {"sensor_height_source", p.sensor_height_source},
                       {"tilt_deg", p.tilt_deg},
                       {"scans_measured", p.scans_measured},
                       {"floors_found", p.floors_found},
                       {"height_spread", p.height_spread},
                       {"rings", p.rings},
                       {"ring_spacing_deg", p.ring_spacing_deg},
                       {"lowest_ring_deg", p.lowest_ring_deg},
                       {"preset", p.preset},
                       {"preset_source", p.preset_source},
                       {"seed_radius", p.seed_radius},
                       {"seed_radius_source", p.seed_radius_source}};
  }
  out["warnings"] = s.warnings;
  return out.dump(1) + "\n";
}

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

namespace {

// map.ply's vertex: x y z (double, or float in runs older than the map frame), then the colour.
constexpr std::size_t kPlyAxes = 3;
constexpr std::size_t kPlyColourBytes = 3;  // uchar red, green, blue
const char* const kPlyAxisNames[kPlyAxes] = {"x", "y", "z"};

template <class Scalar>
std::size_t ply_vertex_bytes() {
  return kPlyAxes * sizeof(Scalar) + kPlyColourBytes;
}

// Vertex `i` of the body at `v`: every coordinate finite and within kMaxCoordinate (a header
// saying float over doubles reads as values up to 3e38), or a FieldError naming it.
template <class Scalar>
MapVertex ply_vertex(const char* v, std::size_t i) {
  Scalar xyz[kPlyAxes];
  std::memcpy(xyz, v, sizeof xyz);
  MapVertex out;
  for (std::size_t a = 0; a < kPlyAxes; ++a) {
    out.p[static_cast<Eigen::Index>(a)] =
        bounded_coordinate(static_cast<double>(xyz[a]), item("vertex", i) + "." + kPlyAxisNames[a]);
  }
  const char* colour = v + sizeof xyz;
  out.r = static_cast<std::uint8_t>(colour[0]), out.g = static_cast<std::uint8_t>(colour[1]),
  out.b = static_cast<std::uint8_t>(colour[2]);
  return out;
}

// The `count` vertices of the body at byte `at` of `bytes`, which must end with the last one:
// a body short of the count, or bytes after it (a header saying float over doubles, a file
// appended to), is an InputError naming the file and the byte.
template <class Scalar>
std::vector<MapVertex> ply_vertices(const std::string& path, const std::string& bytes, std::size_t at,
                                    std::size_t count) {
  const std::size_t stride = ply_vertex_bytes<Scalar>(), body = bytes.size() - at;
  if (body / stride < count) {
    throw input_error(path, 0,
                      "holds " + std::to_string(body / stride) + " vertices of " + std::to_string(stride) +
                          " bytes from byte " + std::to_string(at) + ", its header says " +
                          std::to_string(count));
  }
  if (body != count * stride) {  // no overflow: count * stride <= body
    throw input_error(path, 0,
                      std::to_string(body - count * stride) + " bytes after the last of the header's " +
                          std::to_string(count) + " vertices of " + std::to_string(stride) +
                          " bytes, from byte " + std::to_string(at + count * stride) +
                          " (are the properties' types the body's?)");
  }
  std::vector<MapVertex> out(count);
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t offset = at + i * stride;
    try {
      out[i] = ply_vertex<Scalar>(bytes.data() + offset, i);
    } catch (const FieldError& e) {
      throw input_error(path, 0, std::string("byte ") + std::to_string(offset) + ": " + e.what());
    }
  }
  return out;
}

}  // namespace

std::vector<MapVertex> read_map_ply(const std::string& path) {
  const std::string bytes = read_text_file(path);
  const std::string end = "end_header\n";
  const std::size_t body = bytes.find(end);
  if (bytes.rfind("ply\nformat binary_little_endian 1.0\n", 0) != 0 || body == std::string::npos) {
    throw input_error(path, 1, "not a binary little-endian PLY file");
  }
  std::istringstream header(bytes.substr(0, body));
  std::size_t count = 0;
  std::vector<std::string> properties;
  int line_no = 0;
  for (std::string line; std::getline(header, line);) {
    ++line_no;
    std::istringstream words(line);
    std::string key, a, b;
    words >> key >> a >> b;
    if (key == "element" && a == "vertex") {
      unsigned long long n = 0;
      const auto [ptr, ec] = std::from_chars(b.data(), b.data() + b.size(), n);
      if (ec != std::errc() || ptr != b.data() + b.size())
        throw input_error(path, line_no, "vertex count '" + printable(b) + "' is not a whole number");
      count = static_cast<std::size_t>(n);
    }
    if (key == "property") properties.push_back(a + " " + b);
  }
  const bool doubles = properties == std::vector<std::string>{"double x",  "double y",    "double z",
                                                              "uchar red", "uchar green", "uchar blue"};
  const bool floats = properties == std::vector<std::string>{"float x",   "float y",     "float z",
                                                             "uchar red", "uchar green", "uchar blue"};
  if (!doubles && !floats)
    throw input_error(path, 0, "vertices are not x y z (float or double) then red green blue (uchar)");
  const std::size_t at = body + end.size();
  return doubles ? ply_vertices<double>(path, bytes, at, count) : ply_vertices<float>(path, bytes, at, count);
}

}  // namespace tsgraphs::io
