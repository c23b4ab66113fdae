#include "tsgraphs/room_layer/room_layer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <unordered_set>
#include <utility>

#include "tsgraphs/freespace/obstacle_points.hpp"
#include "tsgraphs/ground/ground_slope.hpp"

namespace tsgraphs::room_layer {

namespace {

rooms::RoomAssociationConfig association_for(rooms::RoomAssociationConfig config, FreeSpaceMethod method) {
  config.match_by_footprint =
      method != FreeSpaceMethod::esdf;  // S-Graphs+ associates by centre distance only
  // TS-graphs segments the whole level's free space each time: the latest footprint is the
  // most complete one, and one that a newly mapped wall cut smaller is the right one.
  if (method != FreeSpaceMethod::esdf) config.footprint = rooms::FootprintPolicy::latest;
  return config;
}

/// Packs an ESDF slice cell (column, row) into one key.
std::int64_t cell_key(int column, int row) {
  constexpr std::int64_t kRowStride = std::int64_t{1} << 32;
  return static_cast<std::int64_t>(row) * kRowStride + column;
}

std::vector<Eigen::Vector3d> points_of(const std::map<std::int64_t, Eigen::Vector3d>& vertices) {
  std::vector<Eigen::Vector3d> out;
  out.reserve(vertices.size());
  for (const auto& entry : vertices) out.push_back(entry.second);
  return out;
}

}  // namespace

RoomLayer::RoomLayer(RoomLayerSettings settings)
    : settings_(std::move(settings)),
      flush_trigger_(settings_.flush),
      timer_trigger_(settings_.timer),
      map_(association_for(settings_.association, settings_.layer.free_space_method)),
      wall_tops_(settings_.sight.cell) {
  check_config(settings_.layer, "RoomLayer");
}

bool RoomLayer::on_level_floor(const Eigen::Vector3d& floor) {
  if (!floor_track_.empty()) track_length_ += (floor - floor_track_.back().second).head<2>().norm();
  floor_track_.emplace_back(track_length_, floor);
  // Keep the points of the last floor_window of path, and the one before it.
  const double window = settings_.layer.floor_window;
  while (floor_track_.size() > 2 && floor_track_[1].first <= track_length_ - window) floor_track_.pop_front();
  double rise = 0.0;
  for (const auto& entry : floor_track_) rise = std::max(rise, std::abs(entry.second.z() - floor.z()));
  return rise <= settings_.layer.max_floor_slope * window;
}

int RoomLayer::level_of(double floor_z) {
  for (std::size_t i = 0; i < levels_.size(); ++i)
    if (std::abs(levels_[i] - floor_z) <= settings_.layer.level_tolerance) return static_cast<int>(i);
  levels_.push_back(floor_z);
  return static_cast<int>(levels_.size()) - 1;
}

bool RoomLayer::robot_space(const RoomLayerInput& input, const Eigen::Vector3d& floor, KeyframeSpace& out) {
  out.position = floor;
  // The segment is the free space within segment_radius of the robot along the free space,
  // so that it does not take in the next room through the wall, only what a door lets in.
  const auto add = [&](std::int64_t key, const Eigen::Vector3d& p, double path_distance) {
    out.cluster.emplace(key, p);
    if (path_distance <= settings_.layer.segment_radius) out.near.emplace(key, p);
  };
  if (esdf()) {
    const freespace::EsdfFreeSpace space = freespace::esdf_free_space(
        input.obstacle_candidates, floor.z(), input.pose.translation(), settings_.esdf);
    const freespace::FreeSpaceCluster* cluster = space.free_space.robot();
    last_cluster_size_ = cluster ? cluster->points.size() : 0;
    if (!cluster) return false;
    for (std::size_t k = 0; k < cluster->vertices.size(); ++k) {
      const int cell = cluster->vertices[k];
      add(cell_key(space.slice.min_i + cell % space.slice.width,
                   space.slice.min_j + cell / space.slice.width),
          cluster->points[k], space.free_space.robot_path_distance[static_cast<std::size_t>(cell)]);
    }
    return true;
  }
  std::vector<Eigen::Vector3d> positions;
  std::vector<int> ids;
  for (const ground::GlobalNode* n : input.nodes->nodes_near(floor, settings_.layer.free_space_radius)) {
    positions.push_back(n->position);
    ids.push_back(n->id);
  }
  const std::vector<Eigen::Vector3d> obstacles =
      freespace::select_obstacles(input.obstacle_candidates, positions, settings_.free_space);
  const freespace::FreeSpace space =
      freespace::traversable_free_space(positions, obstacles, floor, settings_.free_space);
  const freespace::FreeSpaceCluster* cluster = space.robot();
  last_cluster_size_ = cluster ? cluster->points.size() : 0;
  if (!cluster) return false;
  for (std::size_t k = 0; k < cluster->vertices.size(); ++k)
    add(ids[static_cast<std::size_t>(cluster->vertices[k])], cluster->points[k],
        space.robot_path_distance[static_cast<std::size_t>(cluster->vertices[k])]);
  return true;
}

std::vector<RoomEventRecord> RoomLayer::update(const RoomLayerInput& input) {
  const Eigen::Vector3d floor = input.pose.translation() - input.sensor_height * Eigen::Vector3d::UnitZ();
  // On a ramp or stairs the robot is between levels: no floor there is a level's, nor are the
  // spaces either level's (a first keyframe half-way up would otherwise found a level there).
  if (!on_level_floor(floor)) return {};
  const int level = level_of(floor.z());
  if (!esdf()) trace(input, level);
  if (settings_.layer.room_trigger == RoomTrigger::timer) return update_timer(input, floor, level);
  KeyframeSpace space;
  const bool in_free_space = robot_space(input, floor, space);
  if (in_free_space && !esdf())
    for (const auto& entry : space.cluster) free_nodes_.insert(static_cast<int>(entry.first));
  // The robot is in a doorway when the free space has no vertex under it (a door narrower
  // than 2 lambda_th has none); leaving it into free space again has passed the doorway.
  const bool passed_doorway = in_free_space && !was_in_free_space_;
  was_in_free_space_ = in_free_space;
  if (!esdf()) {
    // TS-graphs: a step across a mapped wall (through its door) leaves the space for another
    // one, whatever the free space under the robot shows (a high sensor sees little floor).
    // So does a step into another space of the latest segmentation (an open joint, a bend):
    // extracting at every change of space makes one extraction a visit, the same on every lap.
    const Eigen::Vector3d from =
        pending_.empty() ? (last_position_ ? *last_position_ : floor) : pending_.back().position;
    const bool crossed =
        rooms::crosses_wall(from.head<2>(), floor.head<2>(), walls_, floor.z(), settings_.segmentation);
    const bool moved = moved_on(from, floor, level);
    if (segment_level_ == level && (crossed || moved)) {
      for (const KeyframeSpace& held : pending_) commit(held);
      pending_.clear();
      flush_trigger_.reset();
      std::vector<RoomEventRecord> events = extract(input, segment_, segment_level_);
      clear_segment();
      commit(space);
      return events;
    }
    if (!in_free_space) {
      // No free space to measure the aisle by: the keyframe joins the segment's path.
      for (const KeyframeSpace& held : pending_) commit(held);
      pending_.clear();
      commit(space);
      segment_level_ = level;
      return {};
    }
  }
  if (!in_free_space) return {};
  return update_flush(input, std::move(space), level, passed_doorway);
}

void RoomLayer::trace(const RoomLayerInput& input, int level) {
  freespace::SightMapConfig sight = settings_.sight;
  sight.floor_step = settings_.free_space.obstacle_min_height;
  sight.headroom = settings_.free_space.obstacle_max_height;
  auto it = sight_.find(level);
  if (it == sight_.end())
    it = sight_.emplace(level, freespace::SightMap(levels_[static_cast<std::size_t>(level)], sight)).first;
  retrace(input);
  TracedScan scan{input.keyframe, level, input.pose, {}, 0.0};
  const Pose3 to_sensor = input.pose.inverse();
  scan.local.reserve(input.scan_points.size());
  for (const Eigen::Vector3d& p : input.scan_points) {
    const Eigen::Vector3d l = to_sensor * p;
    scan.local.push_back(l.cast<float>());
    scan.reach = std::max(scan.reach, l.norm());
  }
  const std::vector<Eigen::Vector3d> points = map_points(scan);
  it->second.add_scan(input.pose.translation(), points);
  traced_.push_back(std::move(scan));
  judge_wall_tops(input, level, points, it->second);
}

void RoomLayer::judge_wall_tops(const RoomLayerInput& input, int level,
                                const std::vector<Eigen::Vector3d>& points,
                                const freespace::SightMap& sight) {
  // A plane whose top no ray passed above may reach the ceiling (a low sensor sees a wall's
  // foot); only those of this level short of wall_reach_height need the rays' word.
  const rooms::RoomSegmentationConfig& seg = settings_.segmentation;
  const double level_floor = levels_[static_cast<std::size_t>(level)];
  const auto top_of = [](const rooms::WallCandidate& w) {
    return freespace::WallTopRays::Wall{w.id, w.end_a, w.end_b, w.z1};
  };
  std::vector<freespace::WallTopRays::Wall> short_walls, stale_walls;
  for (const rooms::WallCandidate& w : input.walls) {
    if (!rooms::short_of_reach(w, level_floor, seg)) continue;
    // A plane whose rays were recorded before kept scans were traced again is recorded anew
    // from all of them, where their keyframes are now.
    const auto at = wall_tops_at_.find(w.id);
    if (at != wall_tops_at_.end() && at->second != retraced_)
      stale_walls.push_back(top_of(w));
    else
      short_walls.push_back(top_of(w));
    wall_tops_at_[w.id] = retraced_;
  }
  wall_tops_.add_scan(input.pose.translation(), points, short_walls, sight, seg.wall_top_margin,
                      seg.wall_top_beyond);
  if (!stale_walls.empty()) {
    for (const freespace::WallTopRays::Wall& w : stale_walls) wall_tops_.forget(w.id);
    for (const TracedScan& kept : traced_)
      if (kept.level == level)
        wall_tops_.add_scan(kept.traced_at.translation(), map_points(kept), stale_walls, sight,
                            seg.wall_top_margin, seg.wall_top_beyond);
  }
  walls_ = input.walls;
  for (rooms::WallCandidate& w : walls_)
    w.top_seen = wall_tops_.share_above(top_of(w), seg.wall_top_margin) >= seg.wall_top_share;
}

std::vector<RoomEventRecord> RoomLayer::update_timer(const RoomLayerInput& input,
                                                     const Eigen::Vector3d& floor, int level) {
  if (!timer_trigger_.update(input.stamp)) return {};
  KeyframeSpace space;
  if (!robot_space(input, floor, space)) return {};
  if (!esdf())
    for (const auto& entry : space.cluster) free_nodes_.insert(static_cast<int>(entry.first));
  segment_path_ = {floor};
  return extract(input, space.cluster, level);
}

bool RoomLayer::moved_on(const Eigen::Vector3d& from, const Eigen::Vector3d& floor, int level) {
  const int now_in =
      last_segmentation_ && last_segmentation_level_ == level ? space_of(*last_segmentation_, floor) : -1;
  bool moved = false;
  if (now_in >= 0 && last_space_ >= 0 && now_in != last_space_) {
    const double step = (floor - from).head<2>().norm();
    entering_length_ = now_in == entering_space_ ? entering_length_ + step : step;
    entering_space_ = now_in;
    moved = entering_length_ >= settings_.layer.min_visit_length;
  } else {
    entering_space_ = -1;
    entering_length_ = 0.0;
  }
  if (now_in >= 0 && (last_space_ < 0 || moved)) last_space_ = now_in;
  return moved;
}

std::vector<RoomEventRecord> RoomLayer::update_flush(const RoomLayerInput& input, KeyframeSpace space,
                                                     int level, bool passed_doorway) {
  std::vector<Eigen::Vector3d> cluster = points_of(space.cluster);
  const rooms::AisleMeasurement aisle = rooms::measure_aisle(cluster, space.position, settings_.aisle);
  const bool new_level = segment_level_ >= 0 && level != segment_level_;
  const rooms::FlushReason reason = flush_trigger_.update(aisle, passed_doorway || new_level);
  pending_.push_back(std::move(space));
  std::vector<RoomEventRecord> events;
  if (reason != rooms::FlushReason::none) {
    // The keyframes before the confirming ones close the old segment.
    const std::size_t starting =
        std::min(pending_.size(), static_cast<std::size_t>(flush_trigger_.starting_keyframes()));
    for (std::size_t k = 0; k + starting < pending_.size(); ++k) commit(pending_[k]);
    // A segment walked less than min_segment_length (a corner, a doorway) is no room of its
    // own: it is carried into the next one.
    if (segment_length_ >= settings_.layer.min_segment_length) {
      if (!segment_.empty() || (!esdf() && !segment_path_.empty()))
        events = extract(input, segment_, segment_level_);
      clear_segment();
    }
    // Of the keyframes that confirmed the change only the latest starts the new segment: the
    // earlier ones stood between the two spaces (in a doorway, at a corner) and see both.
    if (starting > 0) pending_.erase(pending_.begin(), pending_.end() - 1);
  }
  // Keyframes the trigger is not holding join the segment.
  const std::size_t held =
      std::min(pending_.size(), static_cast<std::size_t>(flush_trigger_.pending_keyframes()));
  for (std::size_t k = 0; k + held < pending_.size(); ++k) commit(pending_[k]);
  pending_.erase(pending_.begin(), pending_.end() - static_cast<std::ptrdiff_t>(held));
  segment_level_ = level;
  return events;
}

std::vector<Eigen::Vector3d> RoomLayer::map_points(const TracedScan& scan) {
  std::vector<Eigen::Vector3d> out;
  out.reserve(scan.local.size());
  for (const Eigen::Vector3f& l : scan.local) out.push_back(scan.traced_at * l.cast<double>());
  return out;
}

void RoomLayer::forget_keyframe(int keyframe) {
  // Scans are traced in keyframe order.
  const auto it = std::lower_bound(traced_.begin(), traced_.end(), keyframe,
                                   [](const TracedScan& s, int k) { return s.keyframe < k; });
  if (it == traced_.end() || it->keyframe != keyframe) return;
  sight_.at(it->level).remove_scan(it->traced_at.translation(), map_points(*it));
  traced_.erase(it);
}

void RoomLayer::retrace(const RoomLayerInput& input) {
  bool any = false;
  for (TracedScan& scan : traced_) {
    if (scan.keyframe < 0 || static_cast<std::size_t>(scan.keyframe) >= input.keyframe_poses.size()) continue;
    const Pose3& now = input.keyframe_poses[static_cast<std::size_t>(scan.keyframe)];
    // How far its farthest point has moved: a shift under a cell changes no cell it marks by
    // more than one.
    const double angle = Eigen::AngleAxisd(now.linear() * scan.traced_at.linear().transpose()).angle();
    const double shift =
        (now.translation() - scan.traced_at.translation()).norm() + 2.0 * std::sin(angle / 2.0) * scan.reach;
    if (shift <= settings_.sight.cell) continue;
    freespace::SightMap& sight = sight_.at(scan.level);
    sight.remove_scan(scan.traced_at.translation(), map_points(scan));
    scan.traced_at = now;
    sight.add_scan(scan.traced_at.translation(), map_points(scan));
    any = true;
  }
  if (any) ++retraced_;
}

void RoomLayer::commit(const KeyframeSpace& space) {
  if (last_position_) segment_length_ += (space.position - *last_position_).head<2>().norm();
  last_position_ = space.position;
  segment_path_.push_back(space.position);
  for (const auto& [key, p] : space.near) segment_[key] = p;
}

void RoomLayer::clear_segment() {
  segment_.clear();
  segment_length_ = 0.0;
  last_position_.reset();
  segment_path_.clear();
}

std::vector<RoomEventRecord> RoomLayer::finish(const RoomLayerInput& input) {
  if (settings_.layer.room_trigger != RoomTrigger::flush) return {};
  for (const KeyframeSpace& space : pending_) commit(space);
  pending_.clear();
  std::vector<RoomEventRecord> events;
  if (!esdf() && segment_path_.empty() && !deferred_path_.empty()) segment_path_ = {deferred_path_.back()};
  if ((!segment_.empty() || (!esdf() && !segment_path_.empty())) &&
      (segment_length_ >= settings_.layer.min_segment_length || !deferred_path_.empty()))
    events = extract(input, segment_, segment_level_, true);
  clear_segment();
  return events;
}

int RoomLayer::space_of(const rooms::RoomSegmentation& seg, const Eigen::Vector3d& floor) const {
  return seg.space_at(floor.head<2>(), settings_.free_space.lambda_th + nodes_cell_);
}

void RoomLayer::move_room(int id, const Vec2& center) {
  OrientedRect rect = map_.rooms().at(id).rect;
  rect.center = center;
  map_.set_rect(id, rect);
}

std::vector<RoomEventRecord> RoomLayer::extract(const RoomLayerInput& input, const Vertices& segment,
                                                int level, bool final) {
  std::vector<RoomEventRecord> events;
  std::optional<rooms::ExtractedRoom> room;
  std::vector<Eigen::Vector3d> free_space;
  if (esdf()) {
    // S-Graphs+ pairs the planes the last keyframe sees.
    std::vector<rooms::WallCandidate> seen;
    for (const rooms::WallCandidate& w : input.walls)
      if (std::find(input.keyframe_planes.begin(), input.keyframe_planes.end(), w.id) !=
          input.keyframe_planes.end())
        seen.push_back(w);
    free_space = points_of(segment);
    room = rooms::extract_room_sgraphs(free_space, seen, settings_.sgraphs_extraction);
  } else {
    for (const rooms::ExtractedRoom& space : segmented_spaces(input, segment, segment_path_, level, final)) {
      std::vector<Eigen::Vector3d> inside;
      const Polygon2 footprint = footprint_of(space.rect, space.outline);
      for (const auto& [id, p] : segment) {
        const ground::GlobalNode* n = input.nodes->node(static_cast<int>(id));
        const Eigen::Vector3d q = n != nullptr ? n->position : p;
        if (tsgraphs::contains(footprint, q.head<2>())) inside.push_back(q);
      }
      events.push_back(event_of(input, space, level, std::move(inside)));
    }
    return events;
  }
  if (!room) return events;
  events.push_back(event_of(input, *room, level, std::move(free_space)));
  return events;
}

RoomEventRecord RoomLayer::event_of(const RoomLayerInput& input, const rooms::ExtractedRoom& room, int level,
                                    std::vector<Eigen::Vector3d> free_space) {
  const rooms::RoomAssociation a = map_.add_extraction(room, level);
  RoomEventRecord e;
  e.merged = map_.merge_duplicates();
  e.room_id = a.id;
  for (const auto& [keep, drop] : e.merged)
    if (drop == e.room_id) e.room_id = keep;
  e.stamp = input.stamp;
  e.keyframe = input.keyframe;
  e.is_new = a.is_new;
  e.level = level;
  e.kind = room.kind;
  e.rect = room.rect;
  e.outline = room.outline;
  e.walls = room.wall_ids;
  e.free_space = std::move(free_space);
  if (!room.one_sided) e.factor_walls = room.wall_ids;
  e.walls.insert(e.walls.end(), room.end_wall_ids.begin(), room.end_wall_ids.end());
  return e;
}

namespace {

/// The path's length in each space of `seg`.
std::map<int, double> walked_lengths(const rooms::RoomSegmentation& seg,
                                     const std::vector<Eigen::Vector3d>& path, double reach, double cell,
                                     double min_visit_length) {
  // Each step between floor points is cut into pieces of a raster cell (a keyframe's step is
  // as long as a short visit: a step into a store and back must not count as a step through its
  // door). A piece counts for the space of one of its
  // step's ends only: deferred points are a subset of an earlier path, and the chord between
  // two of them crosses what the robot walked round. The robot walks nearer the walls than
  // lambda at times, so a point off every space takes the nearest one within lambda plus a
  // node's reach.
  std::map<int, double> walked;
  // No more pieces than the raster has cells across: beyond it no space is found anyway.
  const double across = std::max(1.0, static_cast<double>(seg.frame.cols + seg.frame.rows));
  for (std::size_t k = 1; k < path.size(); ++k) {
    const Vec2 a = path[k - 1].head<2>(), b = path[k].head<2>();
    const int end_a = seg.space_at(a, reach), end_b = seg.space_at(b, reach);
    const double length = (b - a).norm();
    const int pieces = static_cast<int>(std::clamp(std::ceil(length / cell), 1.0, across));
    for (int j = 0; j < pieces; ++j) {
      const int s = seg.space_at(a + (b - a) * ((j + 0.5) / pieces), reach);
      if (s >= 0 && (s == end_a || s == end_b)) walked[s] += length / pieces;
    }
  }
  if (path.size() == 1) {
    const int s = seg.space_at(path.front().head<2>(), reach);
    if (s >= 0) walked[s] = min_visit_length;
  }
  return walked;
}

}  // namespace

std::vector<Eigen::Vector3d> RoomLayer::with_deferred_path(std::vector<Eigen::Vector3d> path) {
  std::vector<Eigen::Vector3d> deferred;
  deferred.swap(deferred_path_);
  if (!path.empty()) {
    const double floor = path.front().z();
    std::vector<Eigen::Vector3d> same;
    for (const Eigen::Vector3d& p : deferred)
      (std::abs(p.z() - floor) <= settings_.layer.level_tolerance ? same : deferred_path_).push_back(p);
    path.insert(path.begin(), same.begin(), same.end());
  }
  return path;
}

std::optional<rooms::SegmentationInput> RoomLayer::segmentation_input(const RoomLayerInput& input,
                                                                      const Vertices& segment, int level) {
  // The level's floor: where the segment's free space lies (the median node height), so that a
  // sensor height off by a little does not lose the level; without free space, the level's.
  std::vector<double> heights;
  for (const auto& [id, p] : segment) {
    const ground::GlobalNode* n = input.nodes->node(static_cast<int>(id));
    heights.push_back(n != nullptr ? n->position.z() : p.z());
  }
  rooms::SegmentationInput in;
  in.floor_z = levels_.at(static_cast<std::size_t>(level));
  if (!heights.empty()) {
    std::nth_element(heights.begin(), heights.begin() + static_cast<long>(heights.size() / 2), heights.end());
    in.floor_z = heights[heights.size() / 2];
  }
  // The level's ground: within level_band of its floor and no steeper round about than a floor
  // (max_floor_slope over floor_window, as the path's): a ramp's first metres rise less than
  // the band but are no floor of the level. The ground above the band within the headroom
  // (a ramp, a stair) and the sloped ground are raised.
  const double band = settings_.layer.level_band;
  std::vector<const ground::GlobalNode*> level_nodes;
  std::vector<Eigen::Vector3d> positions, normals;
  for (const ground::GlobalNode* n : input.nodes->nodes_in_height_range(
           in.floor_z - band, in.floor_z + std::max(band, settings_.free_space.obstacle_max_height))) {
    if (n->position.z() > in.floor_z + band) {
      in.raised.push_back(n->position.head<2>());
      continue;
    }
    level_nodes.push_back(n);
    positions.push_back(n->position);
    normals.push_back(n->normal);
  }
  const std::vector<double> slopes = ground::ground_slopes(
      positions, normals, input.nodes->config().cell_size, 0.5 * settings_.layer.floor_window);
  std::unordered_set<int> sloped;
  for (std::size_t i = 0; i < level_nodes.size(); ++i) {
    const bool level = slopes[i] <= settings_.layer.max_floor_slope;
    (level ? in.ground : in.raised).push_back(level_nodes[i]->position.head<2>());
    if (!level) sloped.insert(level_nodes[i]->id);
  }
  for (int id : free_nodes_) {
    const ground::GlobalNode* n = input.nodes->node(id);
    if (n != nullptr && std::abs(n->position.z() - in.floor_z) <= band && sloped.count(id) == 0)
      in.free_space.push_back(n->position.head<2>());
  }
  in.free_radius = settings_.free_space.lambda_th;
  in.ground_radius = input.nodes->config().cell_size;
  nodes_cell_ = in.ground_radius;
  in.walls = walls_;
  // The raster covers the level's ground and what its rays saw.
  Vec2 lo = Vec2::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  in.extend_bounds(&lo, &hi);
  const auto sight = sight_.find(level);
  if (sight != sight_.end() && sight->second.lo().x() <= sight->second.hi().x()) {
    lo = lo.cwiseMin(sight->second.lo());
    hi = hi.cwiseMax(sight->second.hi());
  }
  if (!(lo.x() <= hi.x())) return std::nullopt;
  in.frame = GridFrame::around(lo, hi, settings_.segmentation.cell, in.free_radius + in.ground_radius);
  if (sight != sight_.end()) {
    in.seen = sight->second.open_cells(in.frame);
    in.known = sight->second.known_cells(in.frame);
  }
  return in;
}

std::vector<rooms::ExtractedRoom> RoomLayer::segmented_spaces(const RoomLayerInput& input,
                                                              const Vertices& segment,
                                                              std::vector<Eigen::Vector3d> path, int level,
                                                              bool final) {
  // The floor points of spaces deferred before (the same level's) come first.
  path = with_deferred_path(std::move(path));
  if (path.empty()) return {};
  const std::optional<rooms::SegmentationInput> in = segmentation_input(input, segment, level);
  if (!in) return {};
  last_segmentation_ = rooms::segment_rooms(*in, settings_.segmentation);
  last_segmentation_level_ = level;
  ++segmentations_;
  const rooms::RoomSegmentation& seg = *last_segmentation_;
  // A mapped room that this segmentation divides (first seen as one space, now two: a bay
  // beside a gallery) follows it, so that its parts are extracted as rooms of their own; one it
  // no longer carries (a first view over what later rays showed to be a void) follows the space
  // it is a view of. Carried: as much of it on spaces as a segmented footprint is on its region.
  {
    std::vector<rooms::ExtractedRoom> spaces;
    for (const rooms::SegmentedSpace& s : seg.spaces) spaces.push_back(s.room);
    map_.follow_segmentation(spaces, level, settings_.segmentation.rect_fill);
  }
  const double reach = in->free_radius + in->ground_radius;
  const std::map<int, double> walked =
      walked_lengths(seg, path, reach, settings_.segmentation.cell, settings_.layer.min_visit_length);
  // The space the robot is in is still being visited: it is extracted once the robot has left
  // it (one extraction a visit, from all it saw), or at the end.
  const Vec2 robot = (input.pose.translation() - input.sensor_height * Eigen::Vector3d::UnitZ()).head<2>();
  const int current = final ? -1 : seg.space_at(robot, reach);
  last_space_ = current;
  entering_space_ = -1;
  entering_length_ = 0.0;
  std::vector<rooms::ExtractedRoom> out;
  for (const auto& [s, length] : walked) {
    if (length < settings_.layer.min_visit_length && s != current) continue;
    const rooms::SegmentedSpace& space = seg.spaces[static_cast<std::size_t>(s)];
    if (s != current && (final || space.frontier <= settings_.layer.max_frontier)) {
      out.push_back(space.room);
      continue;
    }
    for (const Eigen::Vector3d& p : path)
      if (seg.space_at(p.head<2>(), reach) == s) deferred_path_.push_back(p);
  }
  return out;
}

}  // namespace tsgraphs::room_layer
