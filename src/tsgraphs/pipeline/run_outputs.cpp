#include "tsgraphs/pipeline/run_outputs.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <unordered_set>

#include "tsgraphs/core/map_style.hpp"
#include "tsgraphs/core/voxel_grid.hpp"
#include "tsgraphs/io/atomic_write.hpp"
#include "tsgraphs/io/tum.hpp"

namespace tsgraphs::pipeline {
namespace {

constexpr double kOutlineStep = 0.05;  // one outline point per this length (m)
constexpr double kFloorCross = 0.5;    // half the arm of a floor node's cross (m)
// Keyframe points are thinned to this grid in the map, so map.ply stays small on long runs.
constexpr double kMapVoxel = 0.1;

Pose3 moved(Pose3 pose, const Eigen::Vector3d& origin) {
  pose.translation() += origin;
  return pose;
}

void move(Polygon2& polygon, const Vec2& by) {
  for (Vec2& v : polygon) v += by;
}

// Everything of the graph that has a place, from the map frame into the input's (relative
// measurements, normals and ids stay). A zero origin leaves it untouched (0 + -0 is 0).
void move(io::SceneGraph& g, const Eigen::Vector3d& o) {
  if (o.isZero()) return;
  const Vec2 o2 = o.head<2>();
  for (auto& k : g.keyframes) k.pose.t += o, k.odom.t += o;
  for (auto& p : g.planes) {
    p.d -= p.n.dot(o);  // n.x + d = 0 holds for x + o
    if (p.centroid) *p.centroid += o;
    if (p.segment) (*p.segment)[0] += o2, (*p.segment)[1] += o2;
    if (p.z_range) (*p.z_range)[0] += o.z(), (*p.z_range)[1] += o.z();
  }
  for (auto& n : g.traversable_nodes) n.position += o;
  for (auto& r : g.rooms) {
    r.rect.center += o2;
    move(r.polygon, o2);
    for (Eigen::Vector3d& v : r.free_space) v += o;
  }
  for (auto& r : g.room_nodes) r.center += o2;
  for (auto& f : g.floors) f.center += o2;
  for (double& z : g.levels) z += o.z();
  for (auto& e : g.room_planes_edges) e.cluster_center += o2;
}

}  // namespace

PlaneExtent plane_extent(const Plane& plane, const std::vector<Eigen::Vector3f>& points) {
  PlaneExtent e;
  for (const Eigen::Vector3f& p : points) e.centroid += p.cast<double>();
  e.centroid /= static_cast<double>(points.size());
  e.centroid -= plane.signed_distance(e.centroid) * plane.n;  // onto the plane
  Eigen::Vector2d u(-plane.n.y(), plane.n.x());
  if (u.norm() > 0) u.normalize();
  double s0 = 0, s1 = 0;
  e.z0 = e.z1 = e.centroid.z();
  for (const Eigen::Vector3f& p : points) {
    const double s = u.dot(p.head<2>().cast<double>() - e.centroid.head<2>());
    s0 = std::min(s0, s);
    s1 = std::max(s1, s);
    e.z0 = std::min(e.z0, static_cast<double>(p.z()));
    e.z1 = std::max(e.z1, static_cast<double>(p.z()));
  }
  e.a = e.centroid.head<2>() + s0 * u;
  e.b = e.centroid.head<2>() + s1 * u;
  return e;
}

io::SceneGraph scene_graph_of(const Pipeline& pipeline, const Eigen::Vector3d& origin) {
  const graph::SituationalGraph& g = pipeline.graph();
  io::SceneGraph out;
  for (const graph::KeyframeNode& k : g.keyframes())
    out.keyframes.push_back({k.id, k.scan_index, k.stamp, k.accum_distance, io::PoseRecord::of(k.pose),
                             io::PoseRecord::of(k.odom), k.retired ? k.anchor : -1});
  std::map<int, std::vector<int>> observers;
  for (const graph::PlaneEdge& e : g.plane_edges()) observers[e.plane].push_back(e.keyframe);
  for (const auto& [id, p] : g.planes()) {
    io::SceneGraph::Plane plane;
    plane.id = id;
    plane.kind = p.vertical ? "wall" : "horizontal";
    plane.n = p.plane.n;
    plane.d = p.plane.d;
    plane.keyframes = observers[id];
    std::sort(plane.keyframes.begin(), plane.keyframes.end());
    plane.keyframes.erase(std::unique(plane.keyframes.begin(), plane.keyframes.end()), plane.keyframes.end());
    const auto lm = pipeline.plane_map().landmarks().find(id);
    if (lm != pipeline.plane_map().landmarks().end() && !lm->second.points.empty()) {
      const PlaneExtent e = plane_extent(p.plane, lm->second.points);
      plane.num_points = lm->second.points.size();
      plane.centroid = e.centroid;
      if (p.vertical) plane.segment = std::array<Vec2, 2>{e.a, e.b};
      plane.z_range = std::array<double, 2>{e.z0, e.z1};
    }
    out.planes.push_back(std::move(plane));
  }
  for (const graph::BetweenEdge& e : g.odometry_edges())
    out.odometry_edges.push_back({e.from, e.to, io::PoseRecord::of(e.measurement)});
  for (const graph::BetweenEdge& e : g.loop_edges())
    out.loop_edges.push_back({e.from, e.to, e.fitness, io::PoseRecord::of(e.measurement), e.folded});
  for (const LoopClosureRecord& l : pipeline.loop_closures())
    out.loop_closures.push_back(
        {l.edge.from, l.edge.to, l.edge.fitness, io::PoseRecord::of(l.edge.measurement), l.proposer});
  for (const graph::PlaneEdge& e : g.plane_edges())
    out.keyframe_plane_edges.push_back(
        {e.keyframe, e.plane,
         Eigen::Vector4d(e.measurement.n.x(), e.measurement.n.y(), e.measurement.n.z(), e.measurement.d)});
  for (const graph::RoomPlanesEdge& e : g.room_edges())
    out.room_planes_edges.push_back({e.room, rooms::to_string(e.kind), e.planes, e.cluster_center});
  for (const graph::FloorRoomEdge& e : g.floor_room_edges())
    out.floor_room_edges.push_back({e.floor, e.room});
  for (const ground::GlobalNode* n : pipeline.node_map().nodes())
    out.traversable_nodes.push_back(
        {n->id, n->position, n->normal, n->probability, n->observations, n->anchor_keyframe, n->keyframes});
  // Graph nodes of rooms and floors (optimised centres); "rooms" are the room map's
  // footprints, each naming its graph node when it has one.
  for (const auto& [id, r] : g.rooms())
    out.room_nodes.push_back({id, rooms::to_string(r.kind), r.level, r.center});
  for (const auto& [id, f] : g.floors()) out.floors.push_back({id, f.level, f.center});
  // Each room's free space: the vertices of its latest extraction (for drawing).
  std::map<int, const std::vector<Eigen::Vector3d>*> free_space;
  for (const room_layer::RoomEventRecord& e : pipeline.room_events()) free_space[e.room_id] = &e.free_space;
  for (const auto& [id, r] : pipeline.room_map().rooms()) {
    io::SceneGraph::Room room;
    room.id = id;
    room.kind = rooms::to_string(r.kind);
    room.level = r.level;
    room.rect = r.rect;
    room.polygon = r.outline;
    room.walls = r.wall_ids;
    room.extractions = r.extraction_count;
    if (pipeline.room_node_of(id) >= 0) room.node = pipeline.room_node_of(id);
    if (const auto it = free_space.find(id); it != free_space.end()) room.free_space = *it->second;
    out.rooms.push_back(std::move(room));
  }
  out.levels = pipeline.room_layer().levels();
  move(out, origin);
  return out;
}

std::string scene_graph_json(const Pipeline& pipeline, const Eigen::Vector3d& origin) {
  return io::format_scene_graph(scene_graph_of(pipeline, origin));
}

std::vector<int> laps_of(const std::vector<double>& stamps, const std::vector<Pose3>& poses,
                         const std::vector<double>& lap_starts) {
  constexpr double kLapRadius = 1.5;      // m, docs/metrics.md
  constexpr double kLapMinTravel = 20.0;  // m
  std::vector<int> laps(stamps.size(), 1);
  if (!lap_starts.empty()) {
    for (std::size_t i = 0; i < stamps.size(); ++i)
      laps[i] = std::max<int>(
          1, static_cast<int>(std::upper_bound(lap_starts.begin(), lap_starts.end(), stamps[i]) -
                              lap_starts.begin()));
    return laps;
  }
  int lap = 1;
  double travel = 0.0;
  bool away = false;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    if (i > 0) travel += (poses[i].translation() - poses[i - 1].translation()).norm();
    const double from_start = (poses[i].translation() - poses.front().translation()).norm();
    if (travel > kLapMinTravel && from_start > kLapRadius) away = true;
    if (away && from_start <= kLapRadius) {
      ++lap;
      travel = 0.0;
      away = false;
    }
    laps[i] = lap;
  }
  return laps;
}

std::vector<io::RoomEvent> room_events_of(const Pipeline& pipeline, const std::vector<double>& lap_starts,
                                          const Eigen::Vector3d& origin) {
  std::vector<double> stamps;
  pipeline.scan_log().for_each([&](const ScanRecord& s) { stamps.push_back(s.stamp); });
  const std::vector<int> laps = laps_of(stamps, pipeline.trajectory(), lap_starts);
  std::vector<io::RoomEvent> events;
  for (const room_layer::RoomEventRecord& e : pipeline.room_events()) {
    const std::size_t scan = pipeline.graph().keyframes()[e.keyframe].scan_index;
    io::RoomEvent ev;
    ev.t = e.stamp;
    ev.lap = laps.empty() ? 1 : laps[std::min(scan, laps.size() - 1)];
    ev.room_id = e.room_id;
    ev.is_new = e.is_new;
    ev.level = e.level;
    ev.center = e.outline.size() >= 3 ? centroid(e.outline) : e.rect.center;
    ev.rect = e.rect;
    ev.polygon = e.outline;
    ev.walls = e.walls;
    ev.kind = rooms::to_string(e.kind);
    if (!origin.isZero()) {
      ev.center += origin.head<2>();
      ev.rect.center += origin.head<2>();
      move(ev.polygon, origin.head<2>());
    }
    events.push_back(std::move(ev));
  }
  return events;
}

std::string room_events_jsonl(const Pipeline& pipeline, const std::vector<double>& lap_starts,
                              const Eigen::Vector3d& origin) {
  return io::format_room_events(room_events_of(pipeline, lap_starts, origin));
}

io::Timings timings_of(const Pipeline& pipeline) {
  io::Timings t;
  pipeline.scan_log().for_each([&](const ScanRecord& s) {
    t.scans.push_back({s.scan_index, s.stamp, s.keyframe, s.num_points, s.prefilter_ms, s.walls_ms, s.loop_ms,
                       s.frontend_ms, s.warning, s.ground_ms, s.num_ground_nodes, s.ground_tp, s.ground_fp,
                       s.ground_fn, s.rooms_ms});
  });
  for (std::size_t i = 0; i < pipeline.optimizations().size(); ++i) {
    const OptimizationRecord& o = pipeline.optimizations()[i];
    t.optimizations.push_back({i, pipeline.graph().keyframes()[o.after_keyframe].stamp, o.after_keyframe,
                               o.stats.wall_time_s, o.stats.full, o.stats.n_variables, o.stats.n_factors,
                               o.stats.iterations, o.reason, o.active_keyframes});
  }
  return t;
}

std::string timings_csv(const Pipeline& pipeline) { return io::format_timings(timings_of(pipeline)); }

std::string map_ply(const Pipeline& pipeline, const Eigen::Vector3d& origin) {
  struct Vertex {
    Eigen::Vector3f p;  // map frame (near its origin: float32 is precise there)
    Rgb c;
  };
  std::vector<Vertex> vertices;
  // Keyframe points, thinned on a global grid (first come, first kept).
  std::unordered_set<std::uint64_t> occupied;
  const auto& keyframes = pipeline.graph().keyframes();
  for (const graph::KeyframeNode& k : keyframes) {
    const Eigen::Isometry3f T = k.pose.cast<float>();
    for (const Eigen::Vector3f& p : pipeline.keyframe_cloud(k.id).points) {
      const Eigen::Vector3f q = T * p;
      if (occupied.insert(voxel_key(q, 1.0 / kMapVoxel)).second)
        vertices.push_back({q, kKeyframePointColour});
    }
  }
  for (const auto& [id, lm] : pipeline.plane_map().landmarks()) {
    const Rgb c = lm.vertical ? wall_colour(id) : kHorizontalPlaneColour;
    for (const Eigen::Vector3f& p : lm.points) vertices.push_back({p, c});
  }
  for (const ground::GlobalNode* n : pipeline.node_map().nodes())
    vertices.push_back({n->position.cast<float>(), kTraversableNodeColour});
  // Floor nodes: a cross at their centre, on their level.
  for (const auto& [id, f] : pipeline.graph().floors()) {
    const auto& levels = pipeline.room_layer().levels();
    if (f.level < 0 || static_cast<std::size_t>(f.level) >= levels.size()) continue;
    const float z = static_cast<float>(levels[static_cast<std::size_t>(f.level)] + kOutlineLift);
    for (double t = -kFloorCross; t <= kFloorCross; t += kOutlineStep) {
      vertices.push_back(
          {Eigen::Vector3f(static_cast<float>(f.center.x() + t), static_cast<float>(f.center.y()), z),
           kFloorNodeColour});
      vertices.push_back(
          {Eigen::Vector3f(static_cast<float>(f.center.x()), static_cast<float>(f.center.y() + t), z),
           kFloorNodeColour});
    }
  }
  // Room and corridor footprints: their outlines just above their level's floor.
  for (const auto& [id, r] : pipeline.room_map().rooms()) {
    const auto& levels = pipeline.room_layer().levels();
    const float z = static_cast<float>(levels.at(static_cast<std::size_t>(r.level)) + kOutlineLift);
    const Rgb c = r.kind == rooms::RoomKind::room ? kRoomOutlineColour : kCorridorOutlineColour;
    const Polygon2 corners = r.footprint();
    for (std::size_t i = 0; i < corners.size(); ++i) {
      const Vec2& a = corners[i];
      const Vec2& b = corners[(i + 1) % corners.size()];
      const int steps = std::max(1, static_cast<int>(std::ceil((b - a).norm() / kOutlineStep)));
      for (int k = 0; k < steps; ++k) {
        const Vec2 q = a + (b - a) * (static_cast<double>(k) / steps);
        vertices.push_back({Eigen::Vector3f(static_cast<float>(q.x()), static_cast<float>(q.y()), z), c});
      }
    }
  }
  std::string out =
      "ply\nformat binary_little_endian 1.0\ncomment tsgraphs map: grey keyframe points, "
      "coloured wall faces, beige floors and ceilings, magenta traversable nodes, cyan room and orange "
      "corridor outlines, yellow floor-node crosses\nelement vertex " +
      std::to_string(vertices.size()) +
      "\nproperty double x\nproperty double y\nproperty double z\n"
      "property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n";
  const std::size_t header = out.size();
  constexpr std::size_t kVertexBytes = 3 * sizeof(double) + 3;
  out.resize(header + vertices.size() * kVertexBytes);
  char* dst = out.data() + header;
  for (const Vertex& v : vertices) {
    const Eigen::Vector3d p =
        v.p.cast<double>() + origin;  // the input's frame, to the millimetre at UTM coordinates
    std::memcpy(dst, p.data(), 3 * sizeof(double));  // x86 and ARM are little-endian
    dst[24] = static_cast<char>(v.c.r);
    dst[25] = static_cast<char>(v.c.g);
    dst[26] = static_cast<char>(v.c.b);
    dst += kVertexBytes;
  }
  return out;
}

io::RunSummary run_summary_of(const Pipeline& pipeline, const RunInfo& info) {
  io::RunSummary s;
  s.sequence = info.sequence;
  s.num_scans = info.num_scans;
  s.num_skipped = info.num_skipped;
  s.odometry = info.estimated_odometry ? "lidar" : "input";
  s.num_keyframes = pipeline.graph().keyframes().size();
  s.num_planes = pipeline.graph().planes().size();
  s.num_traversable_nodes = pipeline.node_map().size();
  s.num_rooms = pipeline.room_map().rooms().size();
  s.num_room_events = pipeline.room_events().size();
  s.num_loops = pipeline.graph().loop_edges().size();
  s.num_optimizations = pipeline.optimizations().size();
  for (const OptimizationRecord& o : pipeline.optimizations()) s.t_pgo_s += o.stats.wall_time_s;
  s.sequence_duration_s = info.sequence_duration_s;
  s.wall_time_s = info.wall_time_s;
  s.rtf = info.wall_time_s > 0 ? info.sequence_duration_s / info.wall_time_s : 0.0;
  s.peak_rss_mb = info.peak_rss_mb;
  if (const Platform* p = pipeline.platform()) {
    io::RunPlatform r;
    r.sensor_height = p->sensor_height;
    r.sensor_height_source = p->sensor_height_source;
    r.tilt_deg = p->estimate.tilt_deg;
    r.scans_measured = p->estimate.scans_measured;
    r.floors_found = p->estimate.floors_found;
    r.height_spread = p->estimate.height_spread;
    r.rings = p->estimate.beams.rings;
    r.ring_spacing_deg = p->estimate.beams.spacing_deg;
    r.lowest_ring_deg = p->estimate.beams.lowest_deg;
    r.preset = p->preset;
    r.preset_source = p->preset_source;
    r.seed_radius = p->seed_radius;
    r.seed_radius_source = p->seed_radius_source;
    s.platform = r;
  }
  s.warnings = pipeline.warnings();
  return s;
}

void write_run_outputs(const Pipeline& pipeline, const RunInfo& info, const std::string& dir) {
  const std::vector<Pose3> poses = pipeline.trajectory();
  const Eigen::Vector3d& origin = info.map_origin;
  std::vector<io::StampedPose> stamped;
  stamped.reserve(poses.size());
  std::vector<io::StampedPose> odometry;
  odometry.reserve(poses.size());
  pipeline.scan_log().for_each([&](const ScanRecord& r) {
    stamped.push_back(
        {r.stamp, origin.isZero() ? poses[stamped.size()] : moved(poses[stamped.size()], origin)});
    odometry.push_back({r.stamp, origin.isZero() ? r.odom : moved(r.odom, origin)});
  });
  io::write_file_atomic(dir + "/" + run_files::kTrajectory, io::format_tum(stamped));
  io::write_file_atomic(dir + "/" + run_files::kOdometry, io::format_tum(odometry));
  io::write_file_atomic(dir + "/" + run_files::kSceneGraph, scene_graph_json(pipeline, origin));
  io::write_file_atomic(dir + "/" + run_files::kMap, map_ply(pipeline, origin));
  io::write_file_atomic(dir + "/" + run_files::kTimings, timings_csv(pipeline));
  io::write_file_atomic(dir + "/" + run_files::kRoomEvents,
                        room_events_jsonl(pipeline, info.lap_starts, origin));
  io::write_file_atomic(dir + "/" + run_files::kParams, dump_pipeline_config(pipeline.config()));

  io::write_file_atomic(dir + "/" + run_files::kRunInfo,
                        io::format_run_summary(run_summary_of(pipeline, info)));
}

}  // namespace tsgraphs::pipeline
