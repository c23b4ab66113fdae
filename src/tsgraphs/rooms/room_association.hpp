#pragma once
/// The map of rooms: a new extraction that matches a mapped room of the same level (the smaller
/// footprint lies min_overlap inside the other, or centres within room_dist_threshold) is a
/// re-detection of it, not a new room; mapped rooms that have come to match each other are
/// duplicates and are merged.
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "tsgraphs/core/rect.hpp"
#include "tsgraphs/rooms/room.hpp"
#include "tsgraphs/core/config_fields.hpp"

namespace tsgraphs::rooms {

/// What a re-detection does to the mapped footprint.
enum class FootprintPolicy {
  first,   ///< keeps it
  latest,  ///< replaces it
  largest  ///< replaces it when the new one is larger (a room seen more completely)
};
inline const Choices<FootprintPolicy> kFootprintPolicies{{FootprintPolicy::first, "first"},
                                                         {FootprintPolicy::latest, "latest"},
                                                         {FootprintPolicy::largest, "largest"}};

struct RoomAssociationConfig {
  double min_overlap = 0.5;
  double room_dist_threshold = 1.0;
  bool match_by_footprint =
      true;  ///< false: centres only (S-Graphs+); set by the room layer from its mode, not a file key
  FootprintPolicy footprint = FootprintPolicy::largest;

  template <class V>
  void visit(V& v) {
    v("min_overlap", min_overlap, above(0.0, 1.0),
      "footprints of which the smaller has this share of its area inside the other are one room (a room seen "
      "first from its door, later whole; spaces of one segmentation never overlap)");
    v("room_dist_threshold", room_dist_threshold, between(0.0, 1000.0),
      "...or centres within this distance (m); in esdf mode the centre rule alone (S-Graphs+)");
    v("footprint", footprint, kFootprintPolicies,
      "S-Graphs+ mode: a re-detection's footprint: first keeps the mapped one, latest replaces it, largest "
      "replaces it when larger (TS-graphs always takes the latest segmentation)");
  }
};

struct MappedRoom {
  int id = -1;
  OrientedRect rect;
  Polygon2 outline;  ///< the footprint when it is no rectangle (empty: rect)
  int level = 0;
  RoomKind kind = RoomKind::room;
  std::vector<int> wall_ids;
  int extraction_count = 0;  ///< extractions associated with it, the first one included

  Polygon2 footprint() const { return footprint_of(rect, outline); }
  /// The footprint's centre: the rectangle's, or the outline's area centroid.
  Vec2 center() const { return outline.size() >= 3 ? centroid(outline) : rect.center; }
};

struct RoomAssociation {
  int id = -1;
  bool is_new = false;  ///< false: a re-detection of mapped room `id`
};

class RoomMap {
 public:
  /// Throws std::invalid_argument ("KEY must ...") for an unknown config.footprint or a value out of range.
  explicit RoomMap(RoomAssociationConfig config = {});

  /// Id of the mapped room of `level` the footprint matches (the highest Dice; on a tie the
  /// nearer centre, then the lower id), or -1.
  int match(const OrientedRect& rect, int level) const { return match(rect.corners(), rect.center, level); }
  /// The same for any footprint with its centre.
  int match(const Polygon2& footprint, const Vec2& center, int level) const;
  /// Associates an extraction with its mapped room (its count goes up; its footprint follows
  /// config.footprint) or adds it as a new room with the next id.
  RoomAssociation add_extraction(const ExtractedRoom& room, int level);
  /// A later segmentation of `level` (its spaces, which never overlap) that divides a mapped
  /// room or no longer carries it: a mapped room whose footprint holds two or more of `spaces`
  /// (each with min_overlap of its area inside it) takes the footprint of the one of them it
  /// shares the most area with, so that the others are rooms of their own when they are
  /// extracted; one that the spaces cover less than `min_support` of (a stale view over a void or
  /// across a wall) takes the footprint of the space it shares the most with, and is merged as a
  /// duplicate if another room holds that space. Returns the ids it changed.
  std::vector<int> follow_segmentation(const std::vector<ExtractedRoom>& spaces, int level,
                                       double min_support = 0.0);
  /// Pairs (keep, drop) of mapped rooms of one level that match each other; keep is the one with
  /// more extractions (the lower id on a tie). Rooms linked by a chain of matches form one group
  /// with one keep, so every pair can be merged in turn; sorted by (keep, drop).
  std::vector<std::pair<int, int>> find_duplicates() const;
  /// Adds drop's extraction count and wall ids to keep and removes drop.
  void merge(int keep, int drop);
  /// Moves mapped room `id` (after optimisation the back-end moves the room nodes); its
  /// outline moves with the rectangle's centre.
  void set_rect(int id, const OrientedRect& rect);
  /// find_duplicates() then merge() of every pair; returns the pairs merged.
  std::vector<std::pair<int, int>> merge_duplicates();

  const std::map<int, MappedRoom>& rooms() const { return rooms_; }
  const RoomAssociationConfig& config() const { return config_; }

 private:
  bool matches(const Polygon2& a, const Vec2& ca, const Polygon2& b, const Vec2& cb) const;

  RoomAssociationConfig config_;
  std::map<int, MappedRoom> rooms_;
  int next_id_ = 0;
};

}  // namespace tsgraphs::rooms
