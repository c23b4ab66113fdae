#include "tsgraphs/rooms/room_association.hpp"

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <tuple>
#include <utility>

namespace tsgraphs::rooms {

RoomMap::RoomMap(RoomAssociationConfig config) : config_(std::move(config)) {
  if (config_.footprint != "first" && config_.footprint != "latest" && config_.footprint != "largest")
    throw std::invalid_argument("footprint must be first, latest or largest, not '" + config_.footprint + "'");
}

bool RoomMap::matches(const OrientedRect& a, const OrientedRect& b) const {
  return (config_.match_by_dice && dice(a, b) >= config_.min_dice) ||
         (a.center - b.center).norm() <= config_.room_dist_threshold;
}

int RoomMap::match(const OrientedRect& rect, int level) const {
  int best = -1;
  double best_dice = 0.0;
  double best_distance = 0.0;
  for (const auto& [id, room] : rooms_) {  // ascending ids: ties keep the lower one
    if (room.level != level || !matches(rect, room.rect)) continue;
    const double d = dice(rect, room.rect);
    const double dist = (rect.center - room.rect.center).norm();
    if (best < 0 || std::make_tuple(-d, dist) < std::make_tuple(-best_dice, best_distance)) {
      best = id;
      best_dice = d;
      best_distance = dist;
    }
  }
  return best;
}

RoomAssociation RoomMap::add_extraction(const ExtractedRoom& room, int level) {
  const int id = match(room.rect, level);
  if (id >= 0) {
    MappedRoom& mapped = rooms_.at(id);
    ++mapped.extraction_count;
    const bool larger = room.rect.size.prod() > mapped.rect.size.prod();
    if (config_.footprint == "latest" || (config_.footprint == "largest" && larger)) mapped.rect = room.rect;
    return {id, false};
  }
  MappedRoom mapped;
  mapped.id = next_id_++;
  mapped.rect = room.rect;
  mapped.level = level;
  mapped.kind = room.kind;
  mapped.wall_ids = room.wall_ids;
  mapped.extraction_count = 1;
  rooms_.emplace(mapped.id, mapped);
  return {mapped.id, true};
}

std::vector<std::pair<int, int>> RoomMap::find_duplicates() const {
  std::vector<const MappedRoom*> list;
  for (const auto& entry : rooms_) list.push_back(&entry.second);
  // Union-find over the match relation, so that chains become one group.
  std::vector<std::size_t> parent(list.size());
  std::iota(parent.begin(), parent.end(), 0);
  const auto root = [&](std::size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  for (std::size_t i = 0; i < list.size(); ++i) {
    for (std::size_t j = i + 1; j < list.size(); ++j) {
      if (list[i]->level == list[j]->level && matches(list[i]->rect, list[j]->rect)) {
        parent[root(j)] = root(i);
      }
    }
  }
  // Keep per group: most extractions, then the lower id (list is in ascending id order).
  std::map<std::size_t, std::size_t> keep;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const auto [it, inserted] = keep.emplace(root(i), i);
    if (!inserted && list[i]->extraction_count > list[it->second]->extraction_count) it->second = i;
  }
  std::vector<std::pair<int, int>> pairs;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::size_t k = keep.at(root(i));
    if (k != i) pairs.emplace_back(list[k]->id, list[i]->id);
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

void RoomMap::merge(int keep, int drop) {
  MappedRoom& kept = rooms_.at(keep);
  const MappedRoom& dropped = rooms_.at(drop);
  kept.extraction_count += dropped.extraction_count;
  for (int w : dropped.wall_ids) {
    if (std::find(kept.wall_ids.begin(), kept.wall_ids.end(), w) == kept.wall_ids.end()) kept.wall_ids.push_back(w);
  }
  rooms_.erase(drop);
}

void RoomMap::set_rect(int id, const OrientedRect& rect) { rooms_.at(id).rect = rect; }

std::vector<std::pair<int, int>> RoomMap::merge_duplicates() {
  const std::vector<std::pair<int, int>> pairs = find_duplicates();
  for (const auto& [keep, drop] : pairs) merge(keep, drop);
  return pairs;
}

}  // namespace tsgraphs::rooms
