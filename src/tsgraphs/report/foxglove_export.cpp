#include "tsgraphs/report/foxglove_export.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/core/map_style.hpp"
#include "tsgraphs/core/pose.hpp"
#include "tsgraphs/mcap/mcap.hpp"
#include "tsgraphs/io/run_folder.hpp"
#include "tsgraphs/io/tum.hpp"

namespace tsgraphs::report {
namespace {

using json = nlohmann::ordered_json;  // keys in the order written: the same run gives the same bytes

constexpr double kLabelLift = 0.6;       // room labels above their outline (m)
constexpr double kWallThickness = 0.05;  // a wall plane drawn as a box this thick (m)
constexpr double kWallAlpha = 0.6;       // walls half seen through, so that the rooms behind them show
constexpr double kLineWidth = 0.05;      // outlines and the trajectory (m)
constexpr double kLabelSize = 0.5;       // text height (m)
constexpr std::size_t kMaxTrajectoryPoints =
    5000;  // the trajectory line thinned to at most this many vertices
// Foxglove's numeric types (foxglove.NumericType).
constexpr int kUint8 = 1, kFloat32 = 7;

// ---- schemas: the fields of Foxglove's published JSON schemas that the export writes ----------

json typed(const char* type) { return json{{"type", type}}; }
json integer(std::optional<long long> min = std::nullopt, std::optional<long long> max = std::nullopt) {
  json j = typed("integer");
  if (min) j["minimum"] = *min;
  if (max) j["maximum"] = *max;
  return j;
}
json object(const std::vector<std::pair<std::string, json>>& properties, const std::string& title = "") {
  json j;
  if (!title.empty()) j["title"] = title;
  j["type"] = "object";
  json props = json::object(), required = json::array();
  for (const auto& [name, schema] : properties) {
    props[name] = schema;
    required.push_back(name);
  }
  j["properties"] = props;
  j["required"] = required;
  j["additionalProperties"] = false;
  return j;
}
json array_of(const json& items) { return json{{"type", "array"}, {"items", items}}; }

std::map<std::string, json> make_schemas() {
  const json time = object({{"sec", integer(0)}, {"nsec", integer(0, 999999999)}}, "time");
  const json duration = object({{"sec", integer()}, {"nsec", integer(0, 999999999)}}, "duration");
  const json vector3 =
      object({{"x", typed("number")}, {"y", typed("number")}, {"z", typed("number")}}, "foxglove.Vector3");
  const json quaternion =
      object({{"x", typed("number")}, {"y", typed("number")}, {"z", typed("number")}, {"w", typed("number")}},
             "foxglove.Quaternion");
  const json pose = object({{"position", vector3}, {"orientation", quaternion}}, "foxglove.Pose");
  const json color =
      object({{"r", typed("number")}, {"g", typed("number")}, {"b", typed("number")}, {"a", typed("number")}},
             "foxglove.Color");
  const json field = object({{"name", typed("string")}, {"offset", integer(0)}, {"type", integer(0, 8)}},
                            "foxglove.PackedElementField");
  const json line = object({{"type", integer(0, 2)},
                            {"pose", pose},
                            {"thickness", typed("number")},
                            {"scale_invariant", typed("boolean")},
                            {"points", array_of(vector3)},
                            {"color", color},
                            {"colors", array_of(color)},
                            {"indices", array_of(integer(0))}},
                           "foxglove.LinePrimitive");
  const json cube = object({{"pose", pose}, {"size", vector3}, {"color", color}}, "foxglove.CubePrimitive");
  const json text = object({{"pose", pose},
                            {"billboard", typed("boolean")},
                            {"font_size", typed("number")},
                            {"scale_invariant", typed("boolean")},
                            {"color", color},
                            {"text", typed("string")}},
                           "foxglove.TextPrimitive");
  const json key_value =
      object({{"key", typed("string")}, {"value", typed("string")}}, "foxglove.KeyValuePair");
  json none = typed("array");  // primitive kinds the export does not write: always empty
  none["maxItems"] = 0;
  const json entity = object({{"timestamp", time},
                              {"frame_id", typed("string")},
                              {"id", typed("string")},
                              {"lifetime", duration},
                              {"frame_locked", typed("boolean")},
                              {"metadata", array_of(key_value)},
                              {"arrows", none},
                              {"cubes", array_of(cube)},
                              {"spheres", none},
                              {"cylinders", none},
                              {"lines", array_of(line)},
                              {"triangles", none},
                              {"texts", array_of(text)},
                              {"models", none}},
                             "foxglove.SceneEntity");
  const json deletion = object({{"timestamp", time}, {"type", integer(0, 1)}, {"id", typed("string")}},
                               "foxglove.SceneEntityDeletion");
  json data = typed("string");
  data["contentEncoding"] = "base64";
  return {
      {"foxglove.FrameTransform", object({{"timestamp", time},
                                          {"parent_frame_id", typed("string")},
                                          {"child_frame_id", typed("string")},
                                          {"translation", vector3},
                                          {"rotation", quaternion}},
                                         "foxglove.FrameTransform")},
      {"foxglove.PointCloud", object({{"timestamp", time},
                                      {"frame_id", typed("string")},
                                      {"pose", pose},
                                      {"point_stride", integer(0)},
                                      {"fields", array_of(field)},
                                      {"data", data}},
                                     "foxglove.PointCloud")},
      {"foxglove.SceneUpdate",
       object({{"deletions", array_of(deletion)}, {"entities", array_of(entity)}}, "foxglove.SceneUpdate")},
  };
}

// ---- messages -------------------------------------------------------------------------------

std::uint64_t nanoseconds(double t) { return t > 0 ? static_cast<std::uint64_t>(std::llround(t * 1e9)) : 0; }
json time_of(double t) {
  const std::uint64_t ns = nanoseconds(t);
  return {{"sec", ns / 1000000000ull}, {"nsec", ns % 1000000000ull}};
}
json vec3(const Eigen::Vector3d& v) { return {{"x", v.x()}, {"y", v.y()}, {"z", v.z()}}; }
json quat(const Eigen::Quaterniond& q) { return {{"x", q.x()}, {"y", q.y()}, {"z", q.z()}, {"w", q.w()}}; }
json pose_of(const Eigen::Vector3d& p, const Eigen::Quaterniond& q = Eigen::Quaterniond::Identity()) {
  return {{"position", vec3(p)}, {"orientation", quat(q)}};
}
json rgba(double r, double g, double b, double a = 1.0) { return {{"r", r}, {"g", g}, {"b", b}, {"a", a}}; }
json rgba(const Rgb& c, double a = 1.0) { return rgba(c.r / 255.0, c.g / 255.0, c.b / 255.0, a); }

std::string base64(const std::string& in) {
  static const char* const kDigits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((in.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < in.size(); i += 3) {
    const std::uint32_t n = static_cast<std::uint8_t>(in[i]) << 16 |
                            (i + 1 < in.size() ? static_cast<std::uint8_t>(in[i + 1]) << 8 : 0) |
                            (i + 2 < in.size() ? static_cast<std::uint8_t>(in[i + 2]) : 0);
    out += kDigits[n >> 18 & 63];
    out += kDigits[n >> 12 & 63];
    out += i + 1 < in.size() ? kDigits[n >> 6 & 63] : '=';
    out += i + 2 < in.size() ? kDigits[n & 63] : '=';
  }
  return out;
}

json entity(double t, const std::string& id) {
  return {{"timestamp", time_of(t)},
          {"frame_id", "map"},
          {"id", id},
          {"lifetime", {{"sec", 0}, {"nsec", 0}}},
          {"frame_locked", false},
          {"metadata", json::array()},
          {"arrows", json::array()},
          {"cubes", json::array()},
          {"spheres", json::array()},
          {"cylinders", json::array()},
          {"lines", json::array()},
          {"triangles", json::array()},
          {"texts", json::array()},
          {"models", json::array()}};
}

json line(int type, const std::vector<Eigen::Vector3d>& points, const json& color) {
  json pts = json::array();
  for (const Eigen::Vector3d& p : points) pts.push_back(vec3(p));
  return {{"type", type},
          {"pose", pose_of(Eigen::Vector3d::Zero())},
          {"thickness", kLineWidth},
          {"scale_invariant", false},
          {"points", pts},
          {"color", color},
          {"colors", json::array()},
          {"indices", json::array()}};
}

json text(const Eigen::Vector3d& at, const std::string& what, const json& color) {
  return {{"pose", pose_of(at)},      {"billboard", true}, {"font_size", kLabelSize},
          {"scale_invariant", false}, {"color", color},    {"text", what}};
}

/// A PointCloud of `points` (relative to `origin`), x y z float32 and, with colours, red green blue alpha
/// uint8.
json point_cloud(double t, const Eigen::Vector3d& origin, const std::vector<io::MapVertex>& points,
                 bool coloured) {
  const std::size_t stride = coloured ? 16 : 12;
  std::string data(points.size() * stride, '\0');
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3f p = (points[i].p - origin).cast<float>();
    std::memcpy(data.data() + i * stride, p.data(), 12);  // little-endian, as Foxglove reads it
    if (coloured) {
      const std::uint8_t c[4] = {points[i].r, points[i].g, points[i].b, 255};
      std::memcpy(data.data() + i * stride + 12, c, 4);
    }
  }
  json fields = json::array();
  for (int k = 0; k < 3; ++k)
    fields.push_back({{"name", std::string(1, "xyz"[k])}, {"offset", 4 * k}, {"type", kFloat32}});
  if (coloured) {
    const char* const names[] = {"red", "green", "blue", "alpha"};
    for (int k = 0; k < 4; ++k) fields.push_back({{"name", names[k]}, {"offset", 12 + k}, {"type", kUint8}});
  }
  return {{"timestamp", time_of(t)}, {"frame_id", "map"}, {"pose", pose_of(origin)},
          {"point_stride", stride},  {"fields", fields},  {"data", base64(data)}};
}

/// The height of a level of the run (0 for an unknown one).
double level_height(const io::SceneGraph& graph, int level) {
  return level >= 0 && static_cast<std::size_t>(level) < graph.levels.size()
             ? graph.levels[static_cast<std::size_t>(level)]
             : 0.0;
}

/// The channels of the export, one a topic.
struct Channels {
  std::uint16_t tf = 0, map = 0, nodes = 0, free_space = 0, scene = 0, rooms = 0;
};

/// A room event as the room's entity: its outline, its name and its kind, level, lap and news.
json room_update(const io::RoomEvent& ev, const io::SceneGraph& graph) {
  const bool corridor = ev.kind == "corridor";
  const json colour = rgba(corridor ? kCorridorOutlineColour : kRoomOutlineColour);
  const double z = level_height(graph, ev.level) + kOutlineLift;
  std::vector<Eigen::Vector3d> outline;
  for (const Vec2& v : ev.polygon.size() >= 3 ? ev.polygon : ev.rect.corners())
    outline.emplace_back(v.x(), v.y(), z);
  json ent = entity(ev.t, "room/" + std::to_string(ev.room_id));
  ent["lines"].push_back(line(1, outline, colour));
  ent["texts"].push_back(text(Eigen::Vector3d(ev.center.x(), ev.center.y(), z + kLabelLift),
                              (corridor ? "corridor " : "room ") + std::to_string(ev.room_id), colour));
  ent["metadata"] = json::array({{{"key", "kind"}, {"value", ev.kind}},
                                 {{"key", "level"}, {"value", std::to_string(ev.level)}},
                                 {{"key", "lap"}, {"value", std::to_string(ev.lap)}},
                                 {{"key", "new"}, {"value", ev.is_new ? "true" : "false"}}});
  return {{"deletions", json::array()}, {"entities", json::array({ent})}};
}

/// The sensor's pose in the map frame as a FrameTransform.
json transform(const io::StampedPose& p) {
  return {{"timestamp", time_of(p.t)},
          {"parent_frame_id", "map"},
          {"child_frame_id", "sensor"},
          {"translation", vec3(p.pose.translation())},
          {"rotation", quat(Eigen::Quaterniond(p.pose.linear()))}};
}

/// The traversable nodes as points of their colour.
std::vector<io::MapVertex> traversable_nodes(const io::SceneGraph& graph) {
  std::vector<io::MapVertex> nodes;
  for (const auto& n : graph.traversable_nodes)
    nodes.push_back(
        {n.position, kTraversableNodeColour.r, kTraversableNodeColour.g, kTraversableNodeColour.b});
  return nodes;
}

/// Each room's free space (its latest extraction's vertices), coloured as its outline.
std::vector<io::MapVertex> room_free_space(const io::SceneGraph& graph) {
  std::vector<io::MapVertex> free_space;
  for (const auto& r : graph.rooms) {
    const Rgb c = r.kind == "corridor" ? kCorridorOutlineColour : kRoomOutlineColour;
    for (const Eigen::Vector3d& v : r.free_space) free_space.push_back({v, c.r, c.g, c.b});
  }
  return free_space;
}

/// The mapped walls as thin boxes of their colours.
json walls_entity(const io::SceneGraph& graph, double end) {
  json walls = entity(end, "walls");
  for (const auto& p : graph.planes) {
    if (p.kind != "wall" || !p.segment || !p.z_range) continue;
    const Vec2 a = (*p.segment)[0], b = (*p.segment)[1];
    const double z0 = (*p.z_range)[0], z1 = (*p.z_range)[1];
    const Eigen::Quaterniond yaw(
        Eigen::AngleAxisd(std::atan2(b.y() - a.y(), b.x() - a.x()), Eigen::Vector3d::UnitZ()));
    walls["cubes"].push_back(
        {{"pose",
          pose_of(Eigen::Vector3d(0.5 * (a.x() + b.x()), 0.5 * (a.y() + b.y()), 0.5 * (z0 + z1)), yaw)},
         {"size", vec3(Eigen::Vector3d((b - a).norm(), kWallThickness, std::max(z1 - z0, kWallThickness)))},
         {"color", rgba(wall_colour(p.id), kWallAlpha)}});
  }
  return walls;
}

/// The trajectory as one line, thinned to at most kMaxTrajectoryPoints vertices (the last kept).
json trajectory_entity(const std::vector<io::StampedPose>& trajectory, double end) {
  json path = entity(end, "trajectory");
  std::vector<Eigen::Vector3d> points;
  const std::size_t step =
      std::max<std::size_t>(1, (trajectory.size() + kMaxTrajectoryPoints - 1) / kMaxTrajectoryPoints);
  for (std::size_t i = 0; i < trajectory.size(); i += step)
    points.push_back(trajectory[i].pose.translation());
  if ((trajectory.size() - 1) % step != 0) points.push_back(trajectory.back().pose.translation());
  path["lines"].push_back(line(0, points, rgba(0.1, 0.3, 0.9)));
  return path;
}

/// The floor nodes as labels above their levels.
json floors_entity(const io::SceneGraph& graph, double end) {
  json floors = entity(end, "floors");
  for (const auto& f : graph.floors)
    floors["texts"].push_back(
        text(Eigen::Vector3d(f.center.x(), f.center.y(), level_height(graph, f.level) + 2 * kLabelLift),
             "floor " + std::to_string(f.id), rgba(kFloorNodeColour)));
  return floors;
}

}  // namespace

const std::string& foxglove_schema(const std::string& type) {
  static const std::map<std::string, std::string> kSchemas = [] {
    std::map<std::string, std::string> out;
    for (const auto& [name, schema] : make_schemas()) out[name] = schema.dump();
    return out;
  }();
  const auto it = kSchemas.find(type);
  if (it == kSchemas.end()) throw std::invalid_argument("foxglove_schema: no schema " + type);
  return it->second;
}

namespace {

/// Foxglove's schemas and the export's channels, in the order they are written.
Channels add_channels(mcap::Writer& w) {
  std::map<std::string, std::uint16_t> schema;
  for (const char* type : {"foxglove.FrameTransform", "foxglove.PointCloud", "foxglove.SceneUpdate"})
    schema[type] = w.add_schema(type, "jsonschema", foxglove_schema(type));
  const auto channel = [&](const char* topic, const char* type) {
    return w.add_channel(schema.at(type), topic, "json");
  };
  Channels ch;
  ch.tf = channel("/tf", "foxglove.FrameTransform");
  ch.map = channel("/map", "foxglove.PointCloud");
  ch.nodes = channel("/traversable_nodes", "foxglove.PointCloud");
  ch.free_space = channel("/free_space", "foxglove.PointCloud");
  ch.scene = channel("/scene", "foxglove.SceneUpdate");
  ch.rooms = channel("/rooms", "foxglove.SceneUpdate");
  return ch;
}

}  // namespace

void export_foxglove_mcap(const std::string& run_dir, const std::string& out) {
  namespace fs = std::filesystem;
  const auto file = [&](const char* name) { return (fs::path(run_dir) / name).string(); };
  const std::vector<io::StampedPose> trajectory = io::read_tum(file(io::run_files::kTrajectory));
  const io::SceneGraph graph = io::read_scene_graph(file(io::run_files::kSceneGraph));
  const std::vector<io::RoomEvent> events = io::read_room_events(file(io::run_files::kRoomEvents));
  const std::vector<io::MapVertex> map = io::read_map_ply(file(io::run_files::kMap));
  if (trajectory.empty())
    throw input_error(file(io::run_files::kTrajectory), 0, "no poses: nothing to export");
  const double end = trajectory.back().t;
  // PointCloud positions are float32 relative to the cloud's pose, put near the run's start.
  const Eigen::Vector3d origin = float_safe_origin(trajectory.front().pose.translation());

  mcap::Writer w(out, {"", "tsgraphs", mcap::Compression::zstd, 1u << 20});
  const Channels ch = add_channels(w);
  const auto put = [&](std::uint16_t channel, double t, const json& message) {
    w.write(channel, nanoseconds(t), nanoseconds(t), message.dump());
  };
  // Messages in time order: the room events interleaved with the poses, the maps at the end.
  std::size_t e = 0;
  for (const io::StampedPose& p : trajectory) {
    for (; e < events.size() && events[e].t <= p.t; ++e)
      put(ch.rooms, events[e].t, room_update(events[e], graph));
    put(ch.tf, p.t, transform(p));
  }
  for (; e < events.size(); ++e) put(ch.rooms, events[e].t, room_update(events[e], graph));
  put(ch.map, end, point_cloud(end, origin, map, true));
  put(ch.nodes, end, point_cloud(end, origin, traversable_nodes(graph), false));
  put(ch.free_space, end, point_cloud(end, origin, room_free_space(graph), true));
  put(ch.scene, end,
      {{"deletions", json::array()},
       {"entities", json::array({walls_entity(graph, end), trajectory_entity(trajectory, end),
                                 floors_entity(graph, end)})}});
  w.finish();
}

}  // namespace tsgraphs::report
