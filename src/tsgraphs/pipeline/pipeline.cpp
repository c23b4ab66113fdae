#include "tsgraphs/pipeline/pipeline.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>

#include "tsgraphs/core/polygon.hpp"
#include "tsgraphs/core/voxel_grid.hpp"
#include "tsgraphs/odometry/floor_levelling.hpp"
#include "tsgraphs/pipeline/run_outputs.hpp"
#include "tsgraphs/walls/plane_extraction.hpp"

namespace tsgraphs::pipeline {
namespace {

double ms_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

std::string fixed(double v, int digits) {
  char text[32];
  std::snprintf(text, sizeof text, "%.*f", digits, v);
  return text;
}

// The config checked against every field's declaration before any module takes its part, so
// that a config built in code is refused as a parameter file would be.
PipelineConfig checked(PipelineConfig config) {
  check_config(config, "PipelineConfig");
  return config;
}

}  // namespace

Pipeline::Pipeline(PipelineConfig config)
    : config_(checked(std::move(config))),
      selector_(config_.keyframes),
      mapper_(config_.plane_mapping),
      node_map_(config_.node_map),
      rooms_(config_.rooms),
      optimizer_(config_.optimizer),
      loop_detector_(config_.loop_closure) {}

void Pipeline::set_platform(const std::vector<PointCloud>& scans, const std::vector<Eigen::Vector3d>& ups) {
  if (platform_ || !scan_log_.empty())
    throw std::logic_error("Pipeline::set_platform: once, before the first scan");
  platform_ = resolve_platform(config_.platform, config_.floor_levelling, config_.ground, scans, ups);
  config_.ground = apply_platform(*platform_, config_.ground, config_.ground_keys_given);
  // The run's parameters record what was used: the same file gives the same run again.
  config_.platform.sensor_height = platform_->sensor_height;
  config_.platform.seed_radius = platform_->seed_radius;
  config_.platform.preset = platform_->preset.empty() ? "none" : platform_->preset;
  warnings_.insert(warnings_.end(), platform_->warnings.begin(), platform_->warnings.end());
}

PreparedScan Pipeline::prepare(std::size_t scan_index, double stamp, const PointCloud& scan,
                               const Pose3& odom, bool keyframe_candidate) const {
  if (!platform_) throw std::logic_error("Pipeline::prepare: the platform is not set (set_platform)");
  if (!odom.matrix().allFinite() || !std::isfinite(stamp))
    throw std::invalid_argument("scan " + std::to_string(scan_index) + ": non-finite pose or time");
  PreparedScan out;
  out.record.scan_index = scan_index;
  out.record.stamp = stamp;
  out.record.odom = odom;
  out.input_empty = !scan.has_finite_point();
  out.input_no_points = scan.empty();
  if (keyframe_candidate) run_keyframe_steps(scan, odom, &out);
  return out;
}

void Pipeline::run_keyframe_steps(const PointCloud& scan, const Pose3& odom, PreparedScan* out) const {
  ScanRecord& record = out->record;
  const auto start = std::chrono::steady_clock::now();
  out->cloud = prefilter(scan, config_.prefilter);
  record.num_points = out->cloud.size();
  record.prefilter_ms = ms_since(start);

  const auto ground_start = std::chrono::steady_clock::now();
  out->ground = ground::segment_ground(scan, odom.linear(), config_.ground);
  for (const ground::GroundNode& n : out->ground.nodes) record.num_ground_nodes += n.traversable ? 1 : 0;
  record.ground_ms = ms_since(ground_start);
  if (scan.has_labels()) score_ground(scan, out->ground, &record);
  if (!out->cloud.empty()) {
    const auto walls_start = std::chrono::steady_clock::now();
    out->planes = walls::extract_planes(out->cloud, odom.linear(), config_.plane_extraction);
    record.walls_ms = ms_since(walls_start);
  }
  out->keyframe_steps = true;
}

void Pipeline::score_ground(const PointCloud& scan, const ground::GroundScan& ground,
                            ScanRecord* record) const {
  // Scored over the points the ground layer looks at (its range). Floor more than
  // kOtherStorey below the robot's floor is another storey seen through a void: not this
  // robot's ground, and not scored.
  constexpr double kOtherStorey = 1.0;
  record->ground_tp = record->ground_fp = record->ground_fn = 0;
  const Eigen::Vector3d up = ground.R_level_sensor.transpose().col(2);  // level z in the sensor frame
  const double lowest = -config_.ground.sensor_height - kOtherStorey;
  const double min2 = config_.ground.min_range * config_.ground.min_range;
  const double max2 = config_.ground.max_range * config_.ground.max_range;
  for (std::size_t i = 0; i < scan.size(); ++i) {
    const Eigen::Vector3f& p = scan.points[i];
    if (!p.allFinite()) continue;
    const double r2 = p.squaredNorm();
    if (r2 < min2 || r2 > max2) continue;
    const bool floor = scan.labels[i] == static_cast<std::uint32_t>(PointLabel::kFloor) ||
                       scan.labels[i] == static_cast<std::uint32_t>(PointLabel::kRamp);
    if (floor && up.dot(p.cast<double>()) < lowest) continue;
    const bool ground_point = ground.labels[i] == ground::GroundLabel::kGround;
    record->ground_tp += floor && ground_point;
    record->ground_fp += !floor && ground_point;
    record->ground_fn += floor && !ground_point;
  }
}

const ScanRecord& Pipeline::process(std::size_t scan_index, double stamp, const PointCloud& scan,
                                    const Pose3& odom) {
  if (!platform_) set_platform({scan}, {odom.linear().transpose() * Eigen::Vector3d::UnitZ()});
  return process(prepare(scan_index, stamp, scan, odom, selector_.is_keyframe(odom)), scan);
}

const ScanRecord& Pipeline::process(PreparedScan prepared, const PointCloud& scan) {
  const auto start = std::chrono::steady_clock::now();
  // Thread time of the steps prepare() ran; those run here are inside ms_since(start).
  const double prepared_ms =
      prepared.record.prefilter_ms + prepared.record.ground_ms + prepared.record.walls_ms;
  if (last_odom_) accum_distance_ += (last_odom_->translation() - prepared.record.odom.translation()).norm();
  last_odom_ = prepared.record.odom;

  const bool keyframe = selector_.is_keyframe(prepared.record.odom);
  if (keyframe && !prepared.keyframe_steps) run_keyframe_steps(scan, prepared.record.odom, &prepared);
  ScanRecord record = prepared.record;
  record.reference_keyframe =
      graph_.keyframes().empty() ? -1 : static_cast<int>(graph_.keyframes().size()) - 1;
  if (keyframe) {
    last_ground_ = std::move(prepared.ground);
    if (prepared.cloud.empty()) {
      record.warning = !prepared.input_empty      ? "no point left after prefiltering: skipped"
                       : prepared.input_no_points ? "empty scan: skipped"
                                                  : "no finite point (all NaN): skipped";
    } else {
      selector_.accept(record.odom);
      add_keyframe(record, std::move(prepared.cloud), std::move(prepared.planes));
    }
  } else if (prepared.input_empty) {
    record.warning = prepared.input_no_points ? "empty scan: skipped" : "no finite point (all NaN): skipped";
  }
  record.frontend_ms = prepared_ms + ms_since(start);
  scan_log_.append(record);
  last_record_ = record;
  // The back-end runs after the front-end bookkeeping so that frontend_ms excludes it.
  if (record.keyframe >= 0) {
    const bool loop = !loop_closures_.empty() && loop_closures_.back().edge.to == record.keyframe;
    ++keyframes_since_solve_;
    const int grown = static_cast<int>(graph_.num_active_keyframes()) - active_at_last_full_;
    if (loop) {
      optimize(loop_asks_for_full_solve(loop_closures_.back().edge), "loop");
    } else if (config_.schedule.full_every_keyframes > 0 && grown >= config_.schedule.full_every_keyframes) {
      optimize(true, "periodic");
    } else if (keyframes_since_solve_ >= config_.schedule.optimize_every_keyframes) {
      optimize(false, "schedule");
    }
  }
  return last_record_;
}

void Pipeline::add_keyframe(ScanRecord& record, PointCloud cloud,
                            std::optional<std::vector<walls::PlaneObservation>> planes) {
  graph::KeyframeNode node;
  node.scan_index = record.scan_index;
  node.stamp = record.stamp;
  node.odom = record.odom;
  node.accum_distance = accum_distance_;
  if (graph_.keyframes().empty()) {
    node.pose = record.odom;  // the map frame is the odometry frame at the first keyframe
  } else {
    const graph::KeyframeNode& last = graph_.keyframes().back();
    node.pose = last.pose * (last.odom.inverse() * record.odom);
  }
  const int id = graph_.add_keyframe(node);
  if (id > 0) {
    const graph::KeyframeNode& prev = graph_.keyframes()[id - 1];
    graph_.add_odometry_edge({id - 1, id, prev.odom.inverse() * record.odom, 0.0});
  }
  record.keyframe = id;
  record.reference_keyframe = id;
  keyframe_clouds_.push_back(std::move(cloud));

  const std::size_t ground_nodes = fuse_ground(id);
  const auto walls_start = std::chrono::steady_clock::now();
  const std::size_t walls_seen = add_planes(id, record, std::move(planes));
  record.walls_ms += ms_since(walls_start);
  check_empty_layers(id, ground_nodes, walls_seen);

  const auto rooms_start = std::chrono::steady_clock::now();
  revisited_room_ = -1;
  add_room_events(rooms_.update(room_input(id)));
  record.rooms_ms = ms_since(rooms_start);

  const auto loop_start = std::chrono::steady_clock::now();
  close_loop(id);
  record.loop_ms = ms_since(loop_start);
}

std::size_t Pipeline::fuse_ground(int id) {
  std::vector<ground::NodeObservation> nodes;
  const Eigen::Matrix3d R_sensor_level = last_ground_.R_level_sensor.transpose();
  for (const ground::GroundNode& n : last_ground_.nodes) {
    if (!n.traversable) continue;
    nodes.push_back({R_sensor_level * n.centre.cast<double>(), R_sensor_level * n.normal.cast<double>(),
                     static_cast<double>(n.probability)});
  }
  node_map_.fuse(id, graph_.keyframes()[id].pose, nodes);
  return nodes.size();
}

std::size_t Pipeline::add_planes(int id, const ScanRecord& record,
                                 std::optional<std::vector<walls::PlaneObservation>> planes) {
  const Pose3& T = graph_.keyframes()[id].pose;
  // Only the gravity direction of the rotation matters to the extraction, so planes
  // prepared ahead from the odometry's rotation are the same as those from T's.
  if (!planes)
    planes = walls::extract_planes(keyframe_clouds_.back(), record.odom.linear(), config_.plane_extraction);
  std::size_t walls_seen = 0;
  for (const walls::PlaneObservation& obs : *planes) {
    walls_seen += obs.vertical ? 1 : 0;
    int plane_id = mapper_.associate(obs, T);
    if (plane_id < 0) {
      plane_id = graph_.add_plane(obs.plane.transformed(T), obs.vertical);
      mapper_.add_landmark(plane_id, obs, T, id);
    } else {
      mapper_.add_observation(plane_id, obs, T, id);
    }
    graph_.add_plane_edge({id, plane_id, obs.plane, obs.num_inliers});
  }
  return walls_seen;
}

void Pipeline::close_loop(int id) {
  const auto cloud_of = [this](int k) -> const PointCloud& { return keyframe_clouds_[k]; };
  std::optional<graph::BetweenEdge> loop;
  std::string proposer = "room";
  const auto& mapped = rooms_.room_map().rooms();
  if (config_.room_loop_closure.enabled && revisited_room_ >= 0 && mapped.count(revisited_room_)) {
    const std::vector<int> candidates =
        graph::room_loop_candidates(graph_, id, mapped.at(revisited_room_).footprint(),
                                    config_.loop_closure.min_travel, config_.room_loop_closure);
    loop = loop_detector_.verify(graph_, id, candidates, cloud_of);
  }
  if (!loop) {
    loop = loop_detector_.detect(graph_, id, cloud_of);
    proposer = "distance";
  }
  if (loop) {
    graph_.add_loop_edge(*loop);
    loop_closures_.push_back({*loop, proposer});
  }
}

void Pipeline::check_empty_layers(int keyframe, std::size_t ground_nodes, std::size_t walls) {
  const int n = config_.diagnostics.empty_layer_keyframes;
  if (n <= 0) return;
  const auto count = [](EmptyLayer& layer, bool empty) {
    layer.total += empty ? 1 : 0;
    layer.in_row = empty ? layer.in_row + 1 : 0;
  };
  count(no_ground_, ground_nodes == 0);
  count(no_walls_, walls == 0);
  const std::string span =
      " in " + std::to_string(n) + " keyframes in a row (to keyframe " + std::to_string(keyframe) + ")";
  if (no_ground_.in_row >= n && !no_ground_.warned) {
    no_ground_.warned = true;
    warnings_.push_back("no traversable ground" + span + ": " + no_ground_cause());
  }
  if (no_walls_.in_row >= n && !no_walls_.warned) {
    no_walls_.warned = true;
    warnings_.push_back("no wall" + span + ": " + no_walls_cause(keyframe));
  }
}

std::string Pipeline::no_ground_cause() const {
  // What the ground layer was told against what the latest keyframe shows.
  const odometry::FloorLevel floor =
      odometry::level_from_floor(keyframe_clouds_.back(), config_.floor_levelling);
  const double told = config_.ground.sensor_height;
  if (!floor.found)
    return "no floor found below the sensor there; platform.sensor_height is " + fixed(told, 2) + " m";
  if (std::abs(floor.height - told) > config_.ground.seed_height_tolerance)
    return "the floor is " + fixed(floor.height, 2) +
           " m below the sensor there and platform.sensor_height is " + fixed(told, 2) + " m";
  return "the floor is " + fixed(floor.height, 2) + " m below the sensor there, as platform.sensor_height (" +
         fixed(told, 2) + " m) says: the ground layer's own settings (ground.*) keep every node out";
}

std::string Pipeline::no_walls_cause(int keyframe) const {
  return "no vertical plane of plane_extraction.min_inliers (" +
         std::to_string(config_.plane_extraction.min_inliers) +
         ") points within plane_extraction.max_range (" + fixed(config_.plane_extraction.max_range, 1) +
         " m); keyframe " + std::to_string(keyframe) + " holds " +
         std::to_string(keyframe_clouds_.back().size()) + " points after prefiltering";
}

void Pipeline::optimize(bool full, const std::string& reason) {
  if (graph_.keyframes().size() < 2) return;
  OptimizationRecord rec;
  rec.after_keyframe = static_cast<int>(graph_.keyframes().size()) - 1;
  rec.reason = reason;
  rec.stats = optimizer_.optimize(graph_, full);
  optimizations_.push_back(rec);
  keyframes_since_solve_ = 0;

  std::map<int, Plane> planes;
  for (const auto& [id, node] : graph_.planes()) planes.emplace(id, node.plane);
  const auto pose_of = [this](int k) { return graph_.keyframes().at(k).pose; };
  mapper_.update(planes, pose_of);
  node_map_.update(pose_of);
  move_rooms_with_graph();
  if (config_.schedule.merge_duplicate_planes) {
    for (const auto& [keep, drop] : mapper_.find_duplicates()) {
      if (!graph_.planes().count(keep) || !graph_.planes().count(drop)) continue;
      graph_.merge_planes(keep, drop);
      mapper_.merge(keep, drop, pose_of);
    }
  }
  // Only a loop ties the newest keyframes to the map's earlier passes: a full solve without one
  // corrects no drift.
  if (reason == "loop") corrected_at_ = rec.after_keyframe;
  retire_redundant_keyframes(full, pose_of);
  optimizations_.back().active_keyframes = static_cast<int>(graph_.num_active_keyframes());
  if (full) active_at_last_full_ = optimizations_.back().active_keyframes;
}

bool Pipeline::loop_asks_for_full_solve(const graph::BetweenEdge& loop) const {
  const double sigmas = config_.schedule.full_solve_loop_sigmas;
  if (sigmas <= 0.0) return true;
  const auto& kf = graph_.keyframes();
  // The drift a local solve can take up is that of the keyframes it frees since the last
  // correction (a solve that took in a loop): when that correction lies in the
  // window, the loop's error is judged against its own noise and the odometry noise of those
  // keyframes together; when it lies before the window, against the loop's noise alone.
  const int newest = static_cast<int>(kf.size()) - 1;
  const int first_free = std::max(1, newest + 1 - config_.optimizer.local_window);
  // Retired keyframes count: their odometry noise is folded into their neighbours' edges.
  const int drifting = corrected_at_ >= first_free - 1 ? newest - corrected_at_ : 0;
  const double loop_trans = config_.optimizer.loop_sigma_trans,
               odo_trans = config_.optimizer.odometry_sigma_trans;
  const double loop_rot = config_.optimizer.loop_sigma_rot_deg,
               odo_rot = config_.optimizer.odometry_sigma_rot_deg;
  const double sigma_trans = std::sqrt(loop_trans * loop_trans + drifting * odo_trans * odo_trans);
  const double sigma_rot = std::sqrt(loop_rot * loop_rot + drifting * odo_rot * odo_rot) * M_PI / 180.0;
  const Pose3 error = (kf[loop.from].pose.inverse() * kf[loop.to].pose).inverse() * loop.measurement;
  const double trans = error.translation().norm() / sigma_trans;
  const double rot = Eigen::AngleAxisd(error.linear()).angle() / sigma_rot;
  return std::max(trans, rot) >= sigmas;
}

void Pipeline::retire_redundant_keyframes(bool whole_graph, const std::function<Pose3(int)>& pose_of) {
  const int newest = static_cast<int>(graph_.keyframes().size()) - 1;
  if (config_.keyframe_retirement.enabled) {
    // The local window's keyframes: each has just been optimised with what it saw. A full
    // solve asks again of every keyframe: a room mapped or a duplicate wall merged since a
    // keyframe left the window can make it redundant.
    std::vector<int> candidates;
    const int first = whole_graph ? 1 : std::max(1, newest + 1 - config_.optimizer.local_window);
    for (int k = first; k < newest; ++k)
      if (!graph_.keyframes()[k].retired) candidates.push_back(k);
    const graph::PoseSigmas odometry{config_.optimizer.odometry_sigma_trans,
                                     config_.optimizer.odometry_sigma_rot_deg};
    const graph::PoseSigmas loop{config_.optimizer.loop_sigma_trans, config_.optimizer.loop_sigma_rot_deg};
    const auto in_space = [this](int k) { return in_mapped_space(graph_.keyframes()[k].pose); };
    std::vector<int> retired;
    for (const graph::Retirement& r :
         graph::redundant_keyframes(graph_, candidates, config_.keyframe_retirement, in_space)) {
      graph_.retire_keyframe(r.keyframe, r.anchor, odometry, loop);
      rooms_.forget_keyframe(r.keyframe);
      clouds_to_release_.push_back(r.keyframe);
      retired.push_back(r.keyframe);
    }
    mapper_.forget_keyframes(retired, pose_of);
  }
  // room_input() reads the clouds of the last obstacle_keyframes keyframes.
  const int oldest_read = newest + 1 - config_.rooms.layer.obstacle_keyframes;
  const auto release = [&](int k) {
    if (k >= oldest_read) return false;
    keyframe_clouds_[k] = PointCloud();  // frees its memory
    return true;
  };
  clouds_to_release_.erase(std::remove_if(clouds_to_release_.begin(), clouds_to_release_.end(), release),
                           clouds_to_release_.end());
}

bool Pipeline::in_mapped_space(const Pose3& pose) const {
  const double floor_z = pose.translation().z() - config_.ground.sensor_height;
  const Vec2 xy = pose.translation().head<2>();
  const auto& levels = rooms_.levels();
  for (const auto& [id, room] : rooms_.room_map().rooms()) {
    if (room.level < 0 || static_cast<std::size_t>(room.level) >= levels.size()) continue;
    if (std::abs(levels[static_cast<std::size_t>(room.level)] - floor_z) >
        config_.rooms.layer.level_tolerance)
      continue;
    if (contains(room.footprint(), xy)) return true;
  }
  return false;
}

void Pipeline::finish() {
  // A layer warned about once gets its count over the whole run; one empty in every keyframe of
  // a run too short for the warning in a row is said here, with its cause (before the final
  // solve, which may retire the latest keyframe's cloud).
  const int keyframes = static_cast<int>(graph_.keyframes().size());
  const std::string of = " of " + std::to_string(keyframes) + " keyframes in all";
  const bool warn = config_.diagnostics.empty_layer_keyframes > 0 && keyframes > 0;
  if (no_ground_.warned)
    warnings_.push_back("no traversable ground in " + std::to_string(no_ground_.total) + of);
  else if (warn && no_ground_.total == keyframes)
    warnings_.push_back("no traversable ground in any of the run's " + std::to_string(keyframes) +
                        " keyframes: " + no_ground_cause());
  if (no_walls_.warned)
    warnings_.push_back("no wall in " + std::to_string(no_walls_.total) + of);
  else if (warn && no_walls_.total == keyframes)
    warnings_.push_back("no wall in any of the run's " + std::to_string(keyframes) +
                        " keyframes: " + no_walls_cause(keyframes - 1));
  if (graph_.keyframes().size() >= 2) optimize(true, "final");
  if (!graph_.keyframes().empty()) {
    add_room_events(rooms_.finish(room_input(static_cast<int>(graph_.keyframes().size()) - 1)));
  }
  // Rooms come when the robot leaves a space, which in a long hall may be late: said only of
  // a whole run without one.
  const int n = config_.diagnostics.empty_layer_keyframes;
  if (n > 0 && static_cast<int>(graph_.keyframes().size()) >= n && rooms_.room_map().rooms().empty()) {
    std::size_t mapped_walls = 0;
    for (const auto& [id, lm] : mapper_.landmarks()) mapped_walls += lm.vertical ? 1 : 0;
    const std::string cause = node_map_.size() == 0 ? "no traversable ground"
                              : mapped_walls < 2    ? "fewer than two walls"
                                                    : "no space of the free space bounded by walls";
    warnings_.push_back("no room in " + std::to_string(graph_.keyframes().size()) +
                        " keyframes: " + std::to_string(node_map_.size()) + " traversable nodes and " +
                        std::to_string(mapped_walls) + " walls mapped (" + cause + ")");
  }
}

room_layer::RoomLayerInput Pipeline::room_input(int keyframe) const {
  const graph::KeyframeNode& kf = graph_.keyframes()[keyframe];
  room_layer::RoomLayerInput in;
  in.stamp = kf.stamp;
  in.keyframe = keyframe;
  in.pose = kf.pose;
  in.sensor_height = config_.ground.sensor_height;
  in.nodes = &node_map_;
  // Obstacle candidates: the latest keyframes' clouds in the map, near the robot, thinned.
  const double radius = config_.rooms.layer.free_space_radius + config_.rooms.free_space.lambda_th;
  PointCloud near;
  const int first = std::max(0, keyframe + 1 - config_.rooms.layer.obstacle_keyframes);
  for (int k = first; k <= keyframe; ++k) {
    const Eigen::Isometry3f T = graph_.keyframes()[k].pose.cast<float>();
    for (const Eigen::Vector3f& p : keyframe_clouds_[k].points) {
      const Eigen::Vector3f q = T * p;
      if ((q.head<2>() - kf.pose.translation().head<2>().cast<float>()).norm() <= radius)
        near.points.push_back(q);
    }
  }
  for (const Eigen::Vector3f& p : voxel_downsample(near, config_.rooms.layer.obstacle_voxel).points)
    in.obstacle_candidates.push_back(p.cast<double>());
  // This keyframe's rays for the sight map (TS-graphs).
  if (config_.rooms.layer.free_space_method == room_layer::FreeSpaceMethod::traversable) {
    PointCloud own;
    const Eigen::Isometry3f T = kf.pose.cast<float>();
    for (const Eigen::Vector3f& p : keyframe_clouds_[keyframe].points) own.points.push_back(T * p);
    for (const Eigen::Vector3f& p : voxel_downsample(own, config_.rooms.layer.obstacle_voxel).points)
      in.scan_points.push_back(p.cast<double>());
    in.keyframe_poses.reserve(graph_.keyframes().size());
    for (const auto& k : graph_.keyframes()) in.keyframe_poses.push_back(k.pose);
  }
  // Walls: every mapped vertical plane with its extent. The segmentation covers the whole level,
  // so it draws every wall: without the far ones, the spaces there join rooms that are apart.
  for (const auto& [id, lm] : mapper_.landmarks()) {
    if (!lm.vertical || lm.points.empty()) continue;
    const PlaneExtent e = plane_extent(graph_.planes().at(id).plane, lm.points);
    in.walls.push_back({id, graph_.planes().at(id).plane, e.a, e.b, e.z1 - e.z0, e.z0, e.z1});
  }
  // The keyframe's plane edges were appended with it, after every older keyframe's: read them
  // from the back instead of scanning the whole list at every keyframe.
  const auto& edges = graph_.plane_edges();
  for (auto it = edges.rbegin(); it != edges.rend() && it->keyframe >= keyframe; ++it)
    if (it->keyframe == keyframe) in.keyframe_planes.push_back(it->plane);
  return in;
}

void Pipeline::add_room_events(const std::vector<room_layer::RoomEventRecord>& events) {
  for (const room_layer::RoomEventRecord& e : events) {
    room_events_.push_back(e);
    // A re-detection with the walls of the room's previous extraction: a room-based loop candidate.
    const auto previous = room_walls_.find(e.room_id);
    if (!e.is_new && previous != room_walls_.end() &&
        graph::walls_match(e.walls, previous->second, config_.room_loop_closure))
      revisited_room_ = e.room_id;
    room_walls_[e.room_id] = e.walls;
    // A duplicate merged in the room map: a kept room without a node takes the duplicate's
    // (its footprint then follows the graph's corrections of that place). A kept room with a
    // node keeps it as it is, and the duplicate's node leaves the graph: its room-planes
    // factor names the walls of the footprint the duplicate was extracted with, and given to
    // the kept node it would pull that node, and the kept footprint that moves with it, to a
    // compromise between two rooms (a room dragged out of the building).
    for (const auto& [keep, drop] : e.merged) {
      const auto d = room_nodes_.find(drop);
      if (d == room_nodes_.end()) continue;
      if (room_nodes_.count(keep) == 0) {
        room_nodes_[keep] = d->second;
      } else {
        graph_.remove_room(d->second.node);
      }
      room_nodes_.erase(drop);
    }
    // A room extracted with walls on facing sides (the first time, or a re-detection of one
    // first seen one-sided) becomes a room node with its room-planes factor and a floor-room
    // factor; a one-sided corridor has no pair of planes to make one.
    if (e.factor_walls.empty() || room_nodes_.count(e.room_id)) continue;
    const bool walls_mapped = std::all_of(e.factor_walls.begin(), e.factor_walls.end(),
                                          [this](int w) { return graph_.planes().count(w) > 0; });
    if (!walls_mapped) continue;
    graph::RoomNode node;
    node.center = e.rect.center;
    node.level = e.level;
    node.kind = e.factor_walls.size() == graph::planes_of(rooms::RoomKind::room) ? rooms::RoomKind::room
                                                                                 : rooms::RoomKind::corridor;
    const int id = graph_.add_room(node);
    graph_.add_room_edge({id, node.kind, e.factor_walls, e.rect.center});
    int floor = graph_.floor_of_level(e.level);
    if (floor < 0) floor = graph_.add_floor({-1, e.level, e.rect.center});
    graph_.add_floor_room_edge({floor, id});
    room_nodes_[e.room_id] = {id, node.center};
  }
}

void Pipeline::move_rooms_with_graph() {
  // A mapped room moves by as much as its node moved in the optimisation.
  for (auto& [room_id, link] : room_nodes_) {
    const auto it = graph_.rooms().find(link.node);
    if (it == graph_.rooms().end() || !rooms_.room_map().rooms().count(room_id)) continue;
    const Vec2 moved = it->second.center - link.center;
    link.center = it->second.center;
    rooms_.move_room(room_id, rooms_.room_map().rooms().at(room_id).rect.center + moved);
  }
}

std::vector<Pose3> Pipeline::trajectory() const {
  std::vector<Pose3> poses;
  poses.reserve(scan_log_.size());
  scan_log_.for_each([&](const ScanRecord& s) {
    if (s.reference_keyframe < 0) {
      poses.push_back(s.odom);  // before the first keyframe: the map frame is the odometry frame
      return;
    }
    const graph::KeyframeNode& kf = graph_.keyframes()[s.reference_keyframe];
    poses.push_back(kf.pose * (kf.odom.inverse() * s.odom));
  });
  return poses;
}

}  // namespace tsgraphs::pipeline
