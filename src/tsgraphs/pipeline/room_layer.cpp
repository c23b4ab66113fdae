#include "tsgraphs/pipeline/room_layer.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "tsgraphs/freespace/obstacle_points.hpp"

namespace tsgraphs::pipeline {

namespace {

rooms::RoomAssociationConfig association_for(rooms::RoomAssociationConfig config, const std::string& method) {
  config.match_by_dice = method != "esdf";  // S-Graphs+ associates by centre distance only
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
      map_(association_for(settings_.association, settings_.layer.free_space_method)) {
  const RoomLayerConfig& c = settings_.layer;
  if (c.free_space_method != "traversable" && c.free_space_method != "esdf")
    throw std::invalid_argument("free_space_method must be traversable or esdf, not '" + c.free_space_method + "'");
  if (c.room_trigger != "flush" && c.room_trigger != "timer")
    throw std::invalid_argument("room_trigger must be flush or timer, not '" + c.room_trigger + "'");
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
    const freespace::EsdfFreeSpace space =
        freespace::esdf_free_space(input.obstacle_candidates, floor.z(), input.pose.translation(), settings_.esdf);
    const freespace::FreeSpaceCluster* cluster = space.free_space.robot();
    last_cluster_size_ = cluster ? cluster->points.size() : 0;
    if (!cluster) return false;
    for (std::size_t k = 0; k < cluster->vertices.size(); ++k) {
      const int cell = cluster->vertices[k];
      add(cell_key(space.slice.min_i + cell % space.slice.width, space.slice.min_j + cell / space.slice.width),
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
  const int level = level_of(floor.z());
  if (settings_.layer.room_trigger == "timer") {
    // S-Graphs+: every period, the robot's whole cluster as it is now.
    if (!timer_trigger_.update(input.stamp)) return {};
    KeyframeSpace space;
    if (!robot_space(input, floor, space)) return {};
    return extract(input, space.cluster, space.cluster, level);
  }
  KeyframeSpace space;
  const bool in_free_space = robot_space(input, floor, space);
  // The robot is in a doorway when the free space has no vertex under it (a door narrower
  // than 2 lambda_th has none); leaving it into free space again has passed the doorway.
  const bool passed_doorway = in_free_space && !was_in_free_space_;
  was_in_free_space_ = in_free_space;
  if (!in_free_space) return {};
  return update_flush(input, std::move(space), level, passed_doorway);
}

std::vector<RoomEventRecord> RoomLayer::update_flush(const RoomLayerInput& input, KeyframeSpace space, int level,
                                                     bool passed_doorway) {
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
      if (!segment_.empty()) events = extract(input, segment_, context_, segment_level_);
      clear_segment();
    }
    // Of the keyframes that confirmed the change only the latest starts the new segment: the
    // earlier ones stood between the two spaces (in a doorway, at a corner) and see both.
    if (starting > 0) pending_.erase(pending_.begin(), pending_.end() - 1);
  }
  // Keyframes the trigger is not holding join the segment.
  const std::size_t held = std::min(pending_.size(), static_cast<std::size_t>(flush_trigger_.pending_keyframes()));
  for (std::size_t k = 0; k + held < pending_.size(); ++k) commit(pending_[k]);
  pending_.erase(pending_.begin(), pending_.end() - static_cast<std::ptrdiff_t>(held));
  segment_level_ = level;
  return events;
}

void RoomLayer::commit(const KeyframeSpace& space) {
  if (last_position_) segment_length_ += (space.position - *last_position_).head<2>().norm();
  last_position_ = space.position;
  for (const auto& [key, p] : space.near) segment_[key] = p;
  for (const auto& [key, p] : space.cluster) context_[key] = p;
}

void RoomLayer::clear_segment() {
  segment_.clear();
  context_.clear();
  segment_length_ = 0.0;
  last_position_.reset();
}

std::vector<RoomEventRecord> RoomLayer::finish(const RoomLayerInput& input) {
  if (settings_.layer.room_trigger != "flush") return {};
  for (const KeyframeSpace& space : pending_) commit(space);
  pending_.clear();
  std::vector<RoomEventRecord> events;
  if (!segment_.empty() && segment_length_ >= settings_.layer.min_segment_length)
    events = extract(input, segment_, context_, segment_level_);
  clear_segment();
  return events;
}

void RoomLayer::move_room(int id, const Vec2& center) {
  OrientedRect rect = map_.rooms().at(id).rect;
  rect.center = center;
  map_.set_rect(id, rect);
}

std::vector<RoomEventRecord> RoomLayer::extract(const RoomLayerInput& input, const Vertices& segment,
                                                const Vertices& context, int level) {
  std::vector<RoomEventRecord> events;
  std::optional<rooms::ExtractedRoom> room;
  std::vector<Eigen::Vector3d> free_space;
  if (esdf()) {
    // S-Graphs+ pairs the planes the last keyframe sees.
    std::vector<rooms::WallCandidate> seen;
    for (const rooms::WallCandidate& w : input.walls)
      if (std::find(input.keyframe_planes.begin(), input.keyframe_planes.end(), w.id) != input.keyframe_planes.end())
        seen.push_back(w);
    free_space = points_of(segment);
    room = rooms::extract_room_sgraphs(free_space, seen, settings_.sgraphs_extraction);
  } else {
    // Traversable nodes move with their keyframes: take them where they are now.
    const auto now = [&input](const Vertices& vertices) {
      std::vector<Eigen::Vector3d> points;
      points.reserve(vertices.size());
      for (const auto& [id, p] : vertices) {
        const ground::GlobalNode* n = input.nodes->node(static_cast<int>(id));
        points.push_back(n != nullptr ? n->position : p);
      }
      return points;
    };
    // The context also holds the mapped ground farther along the aisle than the clusters
    // reached (each node once).
    Vertices around = context;
    const Eigen::Vector3d floor = input.pose.translation() - input.sensor_height * Eigen::Vector3d::UnitZ();
    for (const ground::GlobalNode* n : input.nodes->nodes_near(floor, settings_.layer.context_radius))
      around.emplace(n->id, n->position);
    free_space = now(segment);
    room = rooms::extract_room(free_space, now(around), input.walls, settings_.extraction);
  }
  if (!room) return events;
  const rooms::RoomAssociation a = map_.add_extraction(*room, level);
  RoomEventRecord e;
  e.merged = map_.merge_duplicates();
  e.room_id = a.id;
  for (const auto& [keep, drop] : e.merged)
    if (drop == e.room_id) e.room_id = keep;
  e.stamp = input.stamp;
  e.keyframe = input.keyframe;
  e.is_new = a.is_new;
  e.level = level;
  e.kind = room->kind;
  e.rect = room->rect;
  e.walls = room->wall_ids;
  e.free_space = std::move(free_space);
  if (!room->one_sided) e.factor_walls = room->wall_ids;
  e.walls.insert(e.walls.end(), room->end_wall_ids.begin(), room->end_wall_ids.end());
  events.push_back(e);
  return events;
}

}  // namespace tsgraphs::pipeline
