#include "tsgraphs/rooms/room_association.hpp"

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <tuple>
#include <utility>

namespace tsgraphs::rooms {

RoomMap::RoomMap(RoomAssociationConfig config) : config_(std::move(config)) {
  check_config(config_, "RoomMap");
}

namespace {

/// Whether two footprints' bounding boxes overlap (they can have a Dice score above 0).
bool boxes_meet(const Polygon2& a, const Polygon2& b) {
  Vec2 alo = a.front(), ahi = a.front(), blo = b.front(), bhi = b.front();
  for (const Vec2& p : a) {
    alo = alo.cwiseMin(p);
    ahi = ahi.cwiseMax(p);
  }
  for (const Vec2& p : b) {
    blo = blo.cwiseMin(p);
    bhi = bhi.cwiseMax(p);
  }
  return alo.x() <= bhi.x() && blo.x() <= ahi.x() && alo.y() <= bhi.y() && blo.y() <= ahi.y();
}

double footprint_dice(const Polygon2& a, const Polygon2& b) { return boxes_meet(a, b) ? dice(a, b) : 0.0; }

/// The share of the smaller footprint's area inside the other.
double footprint_overlap(const Polygon2& a, const Polygon2& b) {
  const double smaller = std::min(area(a), area(b));
  return boxes_meet(a, b) && smaller > 0.0 ? intersection_area(a, b) / smaller : 0.0;
}

}  // namespace

bool RoomMap::matches(const Polygon2& a, const Vec2& ca, const Polygon2& b, const Vec2& cb) const {
  return (ca - cb).norm() <= config_.room_dist_threshold ||
         (config_.match_by_footprint && footprint_overlap(a, b) >= config_.min_overlap);
}

int RoomMap::match(const Polygon2& footprint, const Vec2& center, int level) const {
  int best = -1;
  double best_dice = 0.0;
  double best_distance = 0.0;
  for (const auto& [id, room] : rooms_) {  // ascending ids: ties keep the lower one
    const Polygon2 other = room.footprint();
    if (room.level != level || !matches(footprint, center, other, room.center())) continue;
    const double d = footprint_dice(footprint, other);
    const double dist = (center - room.center()).norm();
    if (best < 0 || std::make_tuple(-d, dist) < std::make_tuple(-best_dice, best_distance)) {
      best = id;
      best_dice = d;
      best_distance = dist;
    }
  }
  return best;
}

RoomAssociation RoomMap::add_extraction(const ExtractedRoom& room, int level) {
  const Polygon2 footprint = footprint_of(room.rect, room.outline);
  const int id =
      match(footprint, room.outline.size() >= 3 ? centroid(room.outline) : room.rect.center, level);
  if (id >= 0) {
    MappedRoom& mapped = rooms_.at(id);
    ++mapped.extraction_count;
    const bool larger = area(footprint) > area(mapped.footprint());
    if (config_.footprint == FootprintPolicy::latest ||
        (config_.footprint == FootprintPolicy::largest && larger)) {
      mapped.rect = room.rect;
      mapped.outline = room.outline;
    }
    return {id, false};
  }
  MappedRoom mapped;
  mapped.id = next_id_++;
  mapped.rect = room.rect;
  mapped.outline = room.outline;
  mapped.level = level;
  mapped.kind = room.kind;
  mapped.wall_ids = room.wall_ids;
  mapped.extraction_count = 1;
  rooms_.emplace(mapped.id, mapped);
  return {mapped.id, true};
}

std::vector<int> RoomMap::follow_segmentation(const std::vector<ExtractedRoom>& spaces, int level,
                                              double min_support) {
  std::vector<Polygon2> footprints;
  std::vector<double> areas;
  for (const ExtractedRoom& s : spaces) {
    footprints.push_back(footprint_of(s.rect, s.outline));
    areas.push_back(area(footprints.back()));
  }
  std::vector<int> changed;
  for (auto& [id, room] : rooms_) {
    if (room.level != level) continue;
    const Polygon2 mine = room.footprint();
    int held = 0, held_best = -1, best = -1;
    double held_most = 0.0, most = 0.0, supported = 0.0;
    for (std::size_t i = 0; i < spaces.size(); ++i) {
      if (!(areas[i] > 0.0) || !boxes_meet(mine, footprints[i])) continue;
      const double shared = intersection_area(mine, footprints[i]);
      supported += shared;
      if (shared > most) {
        most = shared;
        best = static_cast<int>(i);
      }
      if (shared < config_.min_overlap * areas[i]) continue;
      ++held;
      if (shared > held_most) {
        held_most = shared;
        held_best = static_cast<int>(i);
      }
    }
    // Divided: it holds two spaces or more. Unsupported: the spaces carry less than min_support
    // of it (a first view over what later rays showed to be a void, a view across a wall mapped
    // since); it is a stale view of the space it shares the most with.
    const double own = area(mine);
    int successor = -1;
    if (held >= 2)
      successor = held_best;
    else if (best >= 0 && supported < min_support * own)
      successor = best;
    if (successor < 0) continue;
    room.rect = spaces[static_cast<std::size_t>(successor)].rect;
    room.outline = spaces[static_cast<std::size_t>(successor)].outline;
    changed.push_back(id);
  }
  return changed;
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
      if (list[i]->level == list[j]->level &&
          matches(list[i]->footprint(), list[i]->center(), list[j]->footprint(), list[j]->center())) {
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
    if (std::find(kept.wall_ids.begin(), kept.wall_ids.end(), w) == kept.wall_ids.end())
      kept.wall_ids.push_back(w);
  }
  rooms_.erase(drop);
}

void RoomMap::set_rect(int id, const OrientedRect& rect) {
  MappedRoom& room = rooms_.at(id);
  const Vec2 moved = rect.center - room.rect.center;
  for (Vec2& p : room.outline) p += moved;
  room.rect = rect;
}

std::vector<std::pair<int, int>> RoomMap::merge_duplicates() {
  const std::vector<std::pair<int, int>> pairs = find_duplicates();
  for (const auto& [keep, drop] : pairs) merge(keep, drop);
  return pairs;
}

}  // namespace tsgraphs::rooms
