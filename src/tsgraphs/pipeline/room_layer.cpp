#include "tsgraphs/pipeline/room_layer.hpp"

#include <cmath>

#include "tsgraphs/freespace/obstacle_points.hpp"

namespace tsgraphs::pipeline {

RoomLayer::RoomLayer(RoomLayerConfig config, freespace::TraversableFreeSpaceConfig free_space,
                     rooms::AisleMeasureConfig aisle, rooms::RoomFlushConfig flush,
                     rooms::RoomExtractionConfig extraction, rooms::RoomAssociationConfig association)
    : config_(config),
      free_space_(free_space),
      aisle_(aisle),
      trigger_(flush),
      extraction_(extraction),
      map_(association) {}

int RoomLayer::level_of(double floor_z) {
  for (std::size_t i = 0; i < levels_.size(); ++i)
    if (std::abs(levels_[i] - floor_z) <= config_.level_tolerance) return static_cast<int>(i);
  levels_.push_back(floor_z);
  return static_cast<int>(levels_.size()) - 1;
}

std::vector<RoomEventRecord> RoomLayer::update(const RoomLayerInput& input) {
  const Eigen::Vector3d floor = input.pose.translation() - input.sensor_height * Eigen::Vector3d::UnitZ();
  const int level = level_of(floor.z());

  std::vector<Eigen::Vector3d> positions;
  std::vector<int> ids;
  for (const ground::GlobalNode* n : input.nodes->nodes_near(floor, config_.free_space_radius)) {
    positions.push_back(n->position);
    ids.push_back(n->id);
  }
  const std::vector<Eigen::Vector3d> obstacles =
      freespace::select_obstacles(input.obstacle_candidates, positions, free_space_);
  const freespace::FreeSpace space = freespace::traversable_free_space(positions, obstacles, floor, free_space_);
  const freespace::FreeSpaceCluster* cluster = space.robot();
  last_cluster_size_ = cluster ? cluster->points.size() : 0;

  std::vector<RoomEventRecord> events;
  // The robot is in a doorway when the free space has no vertex under it (a door narrower
  // than 2 lambda_th has none); leaving it into free space again has passed the doorway.
  const bool passed_doorway = cluster && !was_in_free_space_;
  was_in_free_space_ = cluster != nullptr;
  if (!cluster) return events;

  const rooms::AisleMeasurement aisle = rooms::measure_aisle(cluster->points, floor, aisle_);
  const bool new_level = segment_level_ >= 0 && level != segment_level_;
  const rooms::FlushReason reason = trigger_.update(aisle, passed_doorway || new_level);
  if (reason != rooms::FlushReason::none && !segment_.empty()) events = flush(input, segment_level_);
  if (reason != rooms::FlushReason::none) segment_.clear();
  segment_level_ = level;
  for (std::size_t k = 0; k < cluster->vertices.size(); ++k) {
    if ((cluster->points[k] - floor).head<2>().norm() > config_.segment_radius) continue;
    segment_[ids[static_cast<std::size_t>(cluster->vertices[k])]] = cluster->points[k];
  }
  return events;
}

std::vector<RoomEventRecord> RoomLayer::finish(const RoomLayerInput& input) {
  std::vector<RoomEventRecord> events;
  if (!segment_.empty()) events = flush(input, segment_level_);
  segment_.clear();
  return events;
}

std::vector<RoomEventRecord> RoomLayer::flush(const RoomLayerInput& input, int level) {
  // The segment's nodes where they are now (they move with their keyframes).
  std::map<int, Eigen::Vector3d> now;
  for (const ground::GlobalNode* n : input.nodes->nodes()) now.emplace(n->id, n->position);
  std::vector<Eigen::Vector3d> points;
  points.reserve(segment_.size());
  for (const auto& [id, p] : segment_) {
    const auto it = now.find(id);
    points.push_back(it != now.end() ? it->second : p);
  }
  std::vector<RoomEventRecord> events;
  const auto room = rooms::extract_room(points, input.walls, extraction_);
  if (!room) return events;
  const rooms::RoomAssociation a = map_.add_extraction(*room, level);
  int id = a.id;
  for (const auto& [keep, drop] : map_.merge_duplicates())
    if (drop == id) id = keep;
  RoomEventRecord e;
  e.stamp = input.stamp;
  e.keyframe = input.keyframe;
  e.room_id = id;
  e.is_new = a.is_new;
  e.level = level;
  e.kind = room->kind;
  e.rect = room->rect;
  e.walls = room->wall_ids;
  e.walls.insert(e.walls.end(), room->end_wall_ids.begin(), room->end_wall_ids.end());
  events.push_back(e);
  return events;
}

}  // namespace tsgraphs::pipeline
