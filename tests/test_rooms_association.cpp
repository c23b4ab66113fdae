// Room association: re-detections by Dice or centre distance, new rooms, duplicate merging.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "tsgraphs/rooms/room_association.hpp"

namespace tsgraphs::rooms {
namespace {

ExtractedRoom room(Vec2 center, Vec2 size, std::vector<int> walls = {}) {
  ExtractedRoom r;
  r.rect.center = center;
  r.rect.size = size;
  r.wall_ids = std::move(walls);
  return r;
}

TEST(RoomAssociation, DiceOfPointEightAssociates) {
  RoomMap map;  // min_overlap 0.5, room_dist_threshold 1.0
  const ExtractedRoom first = room({0, 0}, {10, 4}, {0, 1, 2, 3});
  EXPECT_EQ(map.add_extraction(first, 0).id, 0);
  const ExtractedRoom again = room({2, 0}, {10, 4});  // centre 2 m away: only the Dice can match
  ASSERT_NEAR(dice(first.rect, again.rect), 0.8, 1e-9);
  const RoomAssociation a = map.add_extraction(again, 0);
  EXPECT_FALSE(a.is_new);
  EXPECT_EQ(a.id, 0);
  ASSERT_EQ(map.rooms().size(), 1u);
  const MappedRoom& mapped = map.rooms().at(0);
  EXPECT_EQ(mapped.extraction_count, 2);
  EXPECT_EQ(mapped.rect.center, Vec2(0, 0));  // the same size: the first footprint is kept
  EXPECT_EQ(mapped.wall_ids, (std::vector<int>{0, 1, 2, 3}));
}

TEST(RoomAssociation, DiceOfPointTwoThreeMetresAwayIsANewRoom) {
  RoomMap map;
  const ExtractedRoom first = room({0, 0}, {5, 4});
  map.add_extraction(first, 0);
  const ExtractedRoom other = room({3, 0}, {2.5, 4});
  ASSERT_NEAR(dice(first.rect, other.rect), 0.2, 1e-9);
  const RoomAssociation a = map.add_extraction(other, 0);
  EXPECT_TRUE(a.is_new);
  EXPECT_EQ(a.id, 1);
  EXPECT_EQ(map.rooms().size(), 2u);
}

TEST(RoomAssociation, ARoomSeenFromItsDoorIsPartOfTheRoomSeenWhole) {
  RoomMap map;
  // A corner of a 10 x 12 m hall seen from its door (Dice 0.14, centres 4.2 m apart), then the hall.
  map.add_extraction(room({-3.5, 4.5}, {3, 3}), 0);
  const ExtractedRoom hall = room({0, 0}, {10, 12});
  ASSERT_LT(dice(map.rooms().at(0).rect, hall.rect), 0.2);
  const RoomAssociation a = map.add_extraction(hall, 0);
  EXPECT_FALSE(a.is_new);
  EXPECT_EQ(a.id, 0);
  // Two views of its sides mapped apart, then the whole: one room.
  RoomMap two;
  two.add_extraction(room({-3.5, 0}, {3, 12}), 0);
  two.add_extraction(room({3.5, 0}, {3, 12}), 0);
  ASSERT_EQ(two.rooms().size(), 2u);
  two.add_extraction(hall, 0);
  EXPECT_EQ(two.merge_duplicates(), (std::vector<std::pair<int, int>>{{0, 1}}));
  EXPECT_EQ(two.rooms().size(), 1u);
  // A neighbour that only shares a strip (a sixth of it) stays a room of its own.
  EXPECT_TRUE(map.add_extraction(room({6, 0}, {3, 12}), 0).is_new);
}

TEST(RoomAssociation, CentreWithinThresholdAssociatesAndLevelsAreSeparate) {
  RoomMap map;
  map.add_extraction(room({0, 0}, {5, 4}), 0);
  // A much smaller footprint (Dice 0.33) whose centre is 0.8 m away: the centre rule matches.
  EXPECT_FALSE(map.add_extraction(room({0.8, 0}, {2, 2}), 0).is_new);
  // The same footprint one level up is another room.
  EXPECT_TRUE(map.add_extraction(room({0, 0}, {5, 4}), 1).is_new);
  EXPECT_EQ(map.match(room({0, 0}, {5, 4}).rect, 1), 1);
}

TEST(RoomAssociation, FootprintPolicyDecidesWhatARedetectionKeeps) {
  const auto after = [](FootprintPolicy policy, Vec2 size) {
    RoomAssociationConfig config;
    config.footprint = policy;
    RoomMap map(config);
    map.add_extraction(room({0, 0}, {5, 4}), 0);
    map.add_extraction(room({0.3, 0.1}, size), 0);
    EXPECT_EQ(map.rooms().at(0).extraction_count, 2);
    return map.rooms().at(0).rect.center;
  };
  EXPECT_EQ(after(FootprintPolicy::first, {5.2, 4}), Vec2(0, 0));
  EXPECT_EQ(after(FootprintPolicy::latest, {4.8, 4}), Vec2(0.3, 0.1));
  EXPECT_EQ(after(FootprintPolicy::largest, {5.2, 4}), Vec2(0.3, 0.1));  // seen more completely
  EXPECT_EQ(after(FootprintPolicy::largest, {4.8, 4}), Vec2(0, 0));
}

TEST(RoomAssociation, CentresOnlyIgnoresTheDice) {
  RoomAssociationConfig config;
  config.match_by_footprint = false;  // S-Graphs+
  RoomMap map(config);
  map.add_extraction(room({0, 0}, {10, 4}), 0);
  EXPECT_TRUE(map.add_extraction(room({2, 0}, {10, 4}), 0).is_new);  // Dice 0.8, centres 2 m apart
  EXPECT_FALSE(map.add_extraction(room({0.9, 0}, {6, 4}), 0).is_new);
}

TEST(RoomAssociation, AMappedRoomALaterSegmentationDividesFollowsIt) {
  RoomMap map;
  // A gallery and the bay beside it, first seen as one space.
  map.add_extraction(room({0, 0}, {10, 4}), 0);
  const ExtractedRoom gallery = room({0, 1}, {10, 2}), bay = room({-4, -1}, {2, 2});
  const ExtractedRoom elsewhere = room({20, 0}, {4, 4});
  // One space over it, or one space and another mostly outside it, divide nothing.
  EXPECT_TRUE(map.follow_segmentation({room({0, 0}, {10, 4.2}), elsewhere}, 0).empty());
  EXPECT_TRUE(map.follow_segmentation({gallery, room({-4, -3}, {2, 4})}, 0).empty());
  EXPECT_TRUE(map.follow_segmentation({gallery, bay}, 1).empty());  // another level's
  EXPECT_EQ(map.rooms().at(0).rect.size, Vec2(10, 4));
  // Two spaces inside it: it becomes the one it shares the most with, the other a room of its own.
  EXPECT_EQ(map.follow_segmentation({bay, gallery, elsewhere}, 0), std::vector<int>{0});
  EXPECT_EQ(map.rooms().at(0).rect.center, Vec2(0, 1));
  EXPECT_EQ(map.rooms().at(0).rect.size, Vec2(10, 2));
  EXPECT_FALSE(map.add_extraction(gallery, 0).is_new);
  const RoomAssociation b = map.add_extraction(bay, 0);
  EXPECT_TRUE(b.is_new);
  EXPECT_TRUE(map.merge_duplicates().empty());
  EXPECT_EQ(map.rooms().size(), 2u);
}

TEST(RoomAssociation, AMappedRoomTheSegmentationNoLongerCarriesFollowsTheSpaceItIsAViewOf) {
  RoomMap map;
  // A corridor, then a first view from it that ran out over a void (later rays went below the floor there).
  map.add_extraction(room({0, 0}, {10, 2}), 0);   // id 0: the corridor
  map.add_extraction(room({2, 2.5}, {3, 4}), 0);  // id 1: 1.5 m^2 on the corridor, 10.5 on the void
  const ExtractedRoom corridor = room({0, 0}, {10, 2}), far = room({20, 0}, {4, 4});
  // Without a share to be carried by, nothing follows; a carried room stays as it is.
  EXPECT_TRUE(map.follow_segmentation({corridor, far}, 0).empty());
  EXPECT_TRUE(map.follow_segmentation({corridor, far}, 0, 0.85) == std::vector<int>{1});
  EXPECT_EQ(map.rooms().at(1).rect.center, Vec2(0, 0));
  EXPECT_EQ(map.rooms().at(0).rect.size, Vec2(10, 2));
  // It is now the corridor seen twice: merged into the room that holds it.
  EXPECT_EQ(map.merge_duplicates(), (std::vector<std::pair<int, int>>{{0, 1}}));
  EXPECT_EQ(map.rooms().size(), 1u);
  // A room that no space touches at all (another part of the level, not segmented now) stays.
  map.add_extraction(room({40, 0}, {4, 4}), 0);  // id 2
  EXPECT_TRUE(map.follow_segmentation({corridor, far}, 0, 0.85).empty());
  EXPECT_EQ(map.rooms().at(2).rect.center, Vec2(40, 0));
}

TEST(RoomAssociation, DuplicatesMergeIntoTheMostExtracted) {
  RoomMap map;
  map.add_extraction(room({0, 0}, {5, 4}, {0, 1}), 0);   // id 0
  map.add_extraction(room({10, 0}, {5, 4}, {2, 3}), 0);  // id 1
  map.add_extraction(room({10.2, 0}, {5, 4}), 0);        // re-detects 1
  map.add_extraction(room({20, 0}, {5, 4}, {4}), 0);     // id 2
  map.add_extraction(room({0, 0}, {5, 4}), 1);           // id 3, another level
  EXPECT_TRUE(map.find_duplicates().empty());
  // Optimisation moves rooms 0 and 2 onto room 1: a chain of three footprints of one room.
  map.set_rect(0, room({9.5, 0}, {5, 4}).rect);
  map.set_rect(2, room({10.6, 0}, {5, 4}).rect);
  const auto pairs = map.merge_duplicates();
  EXPECT_EQ(pairs, (std::vector<std::pair<int, int>>{{1, 0}, {1, 2}}));
  ASSERT_EQ(map.rooms().size(), 2u);
  const MappedRoom& kept = map.rooms().at(1);
  EXPECT_EQ(kept.extraction_count, 4);
  EXPECT_EQ(kept.wall_ids, (std::vector<int>{2, 3, 0, 1, 4}));
  EXPECT_EQ(map.rooms().count(3), 1u);  // the other level's room is untouched
  EXPECT_TRUE(map.find_duplicates().empty());
}

}  // namespace
}  // namespace tsgraphs::rooms
