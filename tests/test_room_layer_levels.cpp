// The room layer's levels: a level is a floor the robot walks on, not a height it passes
// through on a ramp or stairs.
#include <gtest/gtest.h>

#include "tsgraphs/room_layer/room_layer.hpp"

namespace tsgraphs::room_layer {
namespace {

/// Walks `layer` along x with a keyframe every 0.5 m, the floor at floor(s) (m).
template <class Floor>
void walk(RoomLayer* layer, double length, Floor floor) {
  ground::TraversableNodeMap nodes;
  RoomLayerInput in;
  in.nodes = &nodes;
  in.sensor_height = 0.5;
  int k = 0;
  for (double s = 0.0; s <= length; s += 0.5, ++k) {
    in.pose = Pose3::Identity();
    in.pose.translation() = Eigen::Vector3d(s, 0.0, floor(s) + in.sensor_height);
    in.stamp = s;
    in.keyframe = k;
    layer->update(in);
  }
}

TEST(RoomLayer, ARampBetweenTwoFloorsFoundsNoLevelOnIt) {
  // 10 m at 0, an 18 m ramp up 3 m (1:6, the generator's), 10 m at 3 m.
  RoomLayer layer{RoomLayerSettings{}};
  walk(&layer, 38.0, [](double s) { return s < 10.0 ? 0.0 : s < 28.0 ? (s - 10.0) / 6.0 : 3.0; });
  ASSERT_EQ(layer.levels().size(), 2u);
  EXPECT_NEAR(layer.levels()[0], 0.0, 1e-9);
  EXPECT_NEAR(layer.levels()[1], 3.0, 0.1);
}

TEST(RoomLayer, AGentleSlopeIsOneLevel) {
  // A floor falling 1:50 over 30 m (drainage, a slab's sag) stays one level.
  RoomLayer layer{RoomLayerSettings{}};
  walk(&layer, 30.0, [](double s) { return -0.02 * s; });
  EXPECT_EQ(layer.levels().size(), 1u);
}

TEST(RoomLayer, FloorSlopeOutOfRangeIsRefused) {
  RoomLayerSettings settings;
  settings.layer.max_floor_slope = 0.0;
  EXPECT_THROW(RoomLayer{settings}, std::invalid_argument);
  settings = {};
  settings.layer.floor_window = -1.0;
  EXPECT_THROW(RoomLayer{settings}, std::invalid_argument);
}

}  // namespace
}  // namespace tsgraphs::room_layer
