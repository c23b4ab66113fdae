// A run folder's files written: scene_graph.json, rooms_events.jsonl, timings.csv, run_info.json.
#include "tsgraphs/io/run_folder.hpp"

#include <cstdarg>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "tsgraphs/io/run_folder_internal.hpp"

namespace tsgraphs::io {

using namespace run_folder_internal;

namespace {

using nlohmann::json;

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

namespace {

json keyframes_json(const SceneGraph& g) {
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
  return keyframes;
}

json planes_json(const SceneGraph& g) {
  json planes = json::array();
  for (const SceneGraph::Plane& p : g.planes) {
    json plane = {{"id", p.id}, {"kind", p.kind}, {"n", xyz(p.n)}, {"d", p.d}, {"keyframes", p.keyframes}};
    if (p.num_points) plane["num_points"] = *p.num_points;
    if (p.centroid) plane["centroid"] = xyz(*p.centroid);
    if (p.segment) plane["segment"] = {xy((*p.segment)[0]), xy((*p.segment)[1])};
    if (p.z_range) plane["z_range"] = {(*p.z_range)[0], (*p.z_range)[1]};
    planes.push_back(plane);
  }
  return planes;
}

/// Every edge of every kind, kind after kind.
json edges_json(const SceneGraph& g) {
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
  return edges;
}

json traversable_nodes_json(const SceneGraph& g) {
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
  return nodes;
}

json rooms_json(const SceneGraph& g) {
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
  return rooms;
}

json loop_closures_json(const SceneGraph& g) {
  json loop_closures = json::array();
  for (const SceneGraph::LoopClosure& l : g.loop_closures)
    loop_closures.push_back({{"from", l.from},
                             {"to", l.to},
                             {"fitness", l.fitness},
                             {"measurement", pose_json(l.measurement)},
                             {"proposer", l.proposer}});
  return loop_closures;
}

}  // namespace

std::string format_scene_graph(const SceneGraph& g) {
  json room_nodes = json::array();
  for (const SceneGraph::RoomNode& r : g.room_nodes)
    room_nodes.push_back({{"id", r.id}, {"kind", r.kind}, {"level", r.level}, {"center", xy(r.center)}});
  json floors = json::array();
  for (const SceneGraph::Floor& f : g.floors)
    floors.push_back({{"id", f.id}, {"level", f.level}, {"center", xy(f.center)}});
  // nlohmann::json keeps keys sorted: the file's layout since version 1.
  const json doc = {{"format", "tsgraphs-scene-graph"},
                    {"version", 1},
                    {"frame", g.frame},
                    {"keyframes", keyframes_json(g)},
                    {"planes", planes_json(g)},
                    {"traversable_nodes", traversable_nodes_json(g)},
                    {"rooms", rooms_json(g)},
                    {"room_nodes", room_nodes},
                    {"floors", floors},
                    {"levels", g.levels},
                    {"edges", edges_json(g)},
                    {"loop_closures", loop_closures_json(g)}};
  return doc.dump(1) + "\n";
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

}  // namespace tsgraphs::io
