// Keyframe retirement: what SituationalGraph::retire_keyframe folds where, which keyframes
// redundant_keyframes picks on a revisit, and the documented sparsification's bound: the
// corridor loop of graph_test_support.hpp solved as the pipeline does (a local solve every 5
// keyframes, retirement after each, a full solve at the end) against keeping every keyframe.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>
#include <vector>

#include "graph_test_support.hpp"
#include "tsgraphs/graph/graph_optimizer.hpp"
#include "tsgraphs/graph/keyframe_retirement.hpp"

using namespace tsgraphs;
using namespace tsgraphs::graph;
using namespace tsgraphs::graph::test;

namespace {

const PoseSigmas kOdometry{0.05, 0.5}, kLoop{0.05, 0.5};

// Keyframes 0..n-1 a metre apart along x, odometry edges between them, each seeing plane 0.
SituationalGraph line(int n) {
  SituationalGraph g;
  const int plane = g.add_plane(Plane::from_point_normal({0, 2, 0}, {0, -1, 0}), true);
  for (int k = 0; k < n; ++k) {
    KeyframeNode node;
    node.pose = make_pose({double(k), 0, 0}, 0.0);
    node.odom = node.pose;
    node.accum_distance = k;
    g.add_keyframe(node);
    if (k > 0) g.add_odometry_edge({k - 1, k, make_pose({1, 0, 0}, 0.0)});
    g.add_plane_edge(
        {k, plane, Plane::from_point_normal({0, 2, 0}, {0, -1, 0}).transformed(node.pose.inverse()), 50});
  }
  return g;
}

bool near(const Pose3& a, const Pose3& b, double tol = 1e-9) {
  return (a.matrix() - b.matrix()).cwiseAbs().maxCoeff() < tol;
}

// Replays `source` keyframe by keyframe as the pipeline does: a local solve every 5 keyframes
// (window 10), then, with `retire`, the window's redundant keyframes retired; a full solve at
// the end. Everything counts as inside a mapped room.
SituationalGraph replay(const SituationalGraph& source, bool retire) {
  GraphOptimizerConfig oc;
  GraphOptimizer optimizer(oc);
  KeyframeRetirementConfig rc;
  SituationalGraph g;
  std::map<int, int> plane_id;
  const int n = static_cast<int>(source.keyframes().size());
  for (int k = 0; k < n; ++k) {
    KeyframeNode node = source.keyframes()[k];
    if (k > 0) {
      const KeyframeNode& last = g.keyframes().back();
      node.pose = last.pose * (last.odom.inverse() * node.odom);
      g.add_odometry_edge({k - 1, k, source.keyframes()[k - 1].odom.inverse() * node.odom});
    }
    g.add_keyframe(node);
    for (const PlaneEdge& e : source.plane_edges()) {
      if (e.keyframe != k) continue;
      if (!plane_id.count(e.plane))
        plane_id[e.plane] =
            g.add_plane(e.measurement.transformed(node.pose), source.planes().at(e.plane).vertical);
      g.add_plane_edge({k, plane_id.at(e.plane), e.measurement, e.num_inliers});
    }
    if (k % 5 != 4) continue;
    optimizer.optimize(g, false);
    if (!retire) continue;
    std::vector<int> window;
    for (int j = std::max(1, k + 1 - oc.local_window); j < k; ++j) window.push_back(j);
    for (const Retirement& r : redundant_keyframes(g, window, rc, [](int) { return true; }))
      g.retire_keyframe(r.keyframe, r.anchor, {oc.odometry_sigma_trans, oc.odometry_sigma_rot_deg},
                        {oc.loop_sigma_trans, oc.loop_sigma_rot_deg});
  }
  optimizer.optimize(g, true);
  return g;
}

}  // namespace

TEST(KeyframeRetirement, FoldsTheOdometryAndDropsThePlaneEdges) {
  SituationalGraph g = line(4);
  g.keyframes()[2].pose = make_pose({2.1, 0, 0}, 0.0);
  g.retire_keyframe(2, 0, kOdometry, kLoop);
  EXPECT_TRUE(g.keyframes()[2].retired);
  EXPECT_EQ(g.num_active_keyframes(), 3u);
  ASSERT_EQ(g.odometry_edges().size(), 2u);
  const BetweenEdge& joined = g.odometry_edges()[1];
  EXPECT_EQ(joined.from, 1);
  EXPECT_EQ(joined.to, 3);
  EXPECT_EQ(joined.folded, 1);
  EXPECT_TRUE(near(joined.measurement, make_pose({2, 0, 0}, 0.0)));
  // Variances add; the first step's rotation noise, levered by the second step's metre, adds to the
  // translation's.
  const double lever = 0.5 * M_PI / 180.0 * 1.0;
  EXPECT_NEAR(joined.sigmas.trans, std::sqrt(2 * 0.05 * 0.05 + lever * lever), 1e-12);
  EXPECT_NEAR(joined.sigmas.rot_deg, std::sqrt(2.0) * 0.5, 1e-12);
  EXPECT_EQ(g.plane_edges().size(), 3u);
  for (const PlaneEdge& e : g.plane_edges()) EXPECT_NE(e.keyframe, 2);
  // Its pose follows its anchor's.
  g.keyframes()[0].pose = make_pose({0, 1, 0}, 0.0);
  g.update_retired_poses();
  EXPECT_TRUE(near(g.keyframes()[2].pose, make_pose({2.1, 1, 0}, 0.0)));
  // A second retirement folds into the folded edge.
  g.retire_keyframe(1, 0, kOdometry, kLoop);
  ASSERT_EQ(g.odometry_edges().size(), 1u);
  EXPECT_EQ(g.odometry_edges()[0].from, 0);
  EXPECT_EQ(g.odometry_edges()[0].to, 3);
  EXPECT_EQ(g.odometry_edges()[0].folded, 2);
  EXPECT_TRUE(near(g.odometry_edges()[0].measurement, make_pose({3, 0, 0}, 0.0)));
  EXPECT_GT(g.odometry_edges()[0].sigmas.trans, joined.sigmas.trans);
  // The optimizer takes the folded graph and keeps retired poses on their anchors.
  GraphOptimizer optimizer;
  optimizer.optimize(g, true);
  EXPECT_TRUE(near(g.keyframes()[2].pose, g.keyframes()[0].pose * g.keyframes()[2].T_anchor_keyframe));
}

TEST(KeyframeRetirement, LoopEdgesMoveToTheSuccessorAndOnlyTheMostCertainFoldedOneStays) {
  SituationalGraph g = line(6);
  g.add_loop_edge({0, 2, make_pose({2, 0.1, 0}, 0.0), 0.01});
  g.add_loop_edge({1, 3, make_pose({2, 0.2, 0}, 0.0), 0.01});
  g.retire_keyframe(2, 0, kOdometry, kLoop);
  ASSERT_EQ(g.loop_edges().size(), 2u);
  const auto moved = std::find_if(g.loop_edges().begin(), g.loop_edges().end(),
                                  [](const BetweenEdge& e) { return e.folded > 0; });
  ASSERT_NE(moved, g.loop_edges().end());
  EXPECT_EQ(moved->from, 0);
  EXPECT_EQ(moved->to, 3);
  EXPECT_TRUE(near(moved->measurement, make_pose({3, 0.1, 0}, 0.0)));
  EXPECT_GT(moved->sigmas.trans, kLoop.trans);
  // Retiring 3 moves both to 4; the one folded once more is the less certain and goes.
  g.retire_keyframe(3, 1, kOdometry, kLoop);
  ASSERT_EQ(g.loop_edges().size(), 1u);
  EXPECT_EQ(g.loop_edges()[0].from, 1);
  EXPECT_EQ(g.loop_edges()[0].to, 4);
  EXPECT_EQ(g.loop_edges()[0].folded, 1);
  EXPECT_TRUE(near(g.loop_edges()[0].measurement, make_pose({3, 0.2, 0}, 0.0)));
}

TEST(KeyframeRetirement, RefusesWhatCannotBeRetired) {
  SituationalGraph g = line(4);
  EXPECT_THROW(g.retire_keyframe(0, 0, kOdometry, kLoop), std::invalid_argument);  // the anchor of the map
  EXPECT_THROW(g.retire_keyframe(3, 0, kOdometry, kLoop), std::invalid_argument);  // newest: no edge out
  EXPECT_THROW(g.retire_keyframe(2, 2, kOdometry, kLoop), std::invalid_argument);  // anchor not older
  EXPECT_THROW(g.retire_keyframe(4, 0, kOdometry, kLoop), std::invalid_argument);  // unknown
  g.retire_keyframe(1, 0, kOdometry, kLoop);
  EXPECT_THROW(g.retire_keyframe(1, 0, kOdometry, kLoop), std::invalid_argument);  // twice
  EXPECT_THROW(g.retire_keyframe(2, 1, kOdometry, kLoop), std::invalid_argument);  // retired anchor
  // The optimizer refuses an edge to a retired keyframe.
  g.add_loop_edge({1, 3, make_pose({2, 0, 0}, 0.0), 0.01});
  GraphOptimizer optimizer;
  EXPECT_THROW(optimizer.optimize(g, true), std::invalid_argument);
  KeyframeRetirementConfig bad;
  bad.radius = 0.0;
  EXPECT_THROW(redundant_keyframes(g, {2}, bad, [](int) { return true; }), std::invalid_argument);
}

TEST(KeyframeRetirement, OnTheSecondLapEveryKeyframeIsRedundantButOnesThatSeeANewWall) {
  Scenario s = corridor_loop(true);
  GraphOptimizer().optimize(s.graph, true);
  const int n = static_cast<int>(s.graph.keyframes().size());
  const int lap = static_cast<int>(kLap);
  std::vector<int> all;
  for (int k = 0; k < n; ++k) all.push_back(k);
  const KeyframeRetirementConfig config;
  const auto everywhere = [](int) { return true; };
  std::vector<Retirement> r = redundant_keyframes(s.graph, all, config, everywhere);
  // The first lap has no earlier pass; the newest keyframe is never retired.
  ASSERT_EQ(static_cast<int>(r.size()), n - 1 - lap);
  for (const Retirement& x : r) {
    EXPECT_GE(x.keyframe, lap);
    EXPECT_EQ(x.anchor, x.keyframe - lap) << "keyframe " << x.keyframe;
  }
  // Outside mapped rooms nothing is retired with rooms_only; without it, everything above.
  EXPECT_TRUE(redundant_keyframes(s.graph, all, config, [](int) { return false; }).empty());
  KeyframeRetirementConfig anywhere = config;
  anywhere.rooms_only = false;
  EXPECT_EQ(redundant_keyframes(s.graph, all, anywhere, [](int) { return false; }).size(), r.size());
  // A wall only the second lap saw keeps the keyframe that saw it.
  const int new_wall = s.graph.add_plane(Plane::from_point_normal({5, 3, 0}, {0, -1, 0}), true);
  s.graph.add_plane_edge(
      {lap + 5, new_wall,
       s.graph.planes().at(new_wall).plane.transformed(s.graph.keyframes()[lap + 5].pose.inverse()), 50});
  r = redundant_keyframes(s.graph, all, config, everywhere);
  EXPECT_EQ(static_cast<int>(r.size()), n - 2 - lap);
  EXPECT_TRUE(std::none_of(r.begin(), r.end(), [&](const Retirement& x) { return x.keyframe == lap + 5; }));
}

TEST(KeyframeRetirement, OneCallDecidesInIdOrderAgainstWhatStays) {
  // Three laps of ten keyframes along x, each lap 0.3 m further off in y, every keyframe seeing
  // plane 0; one call over the whole graph, as after a full solve. Lap 3 lies nearer lap 2 than
  // lap 1, but lap 2 leaves in the same call: lap 3 must anchor on lap 1.
  SituationalGraph g;
  const Plane wall = Plane::from_point_normal({0, 2, 0}, {0, -1, 0});
  const int plane = g.add_plane(wall, true);
  for (int k = 0; k < 30; ++k) {
    KeyframeNode node;
    node.pose = make_pose({double(k % 10), 0.3 * (k / 10), 0}, 0.0);
    node.odom = node.pose;
    node.accum_distance = k;
    g.add_keyframe(node);
    if (k > 0) g.add_odometry_edge({k - 1, k, g.keyframes()[k - 1].pose.inverse() * node.pose});
    g.add_plane_edge({k, plane, wall.transformed(node.pose.inverse()), 50});
  }
  // A wall first seen on lap 2 at keyframe 15, seen again on lap 3 at keyframe 25.
  const Plane other = Plane::from_point_normal({5, -2, 0}, {0, 1, 0});
  const int seen_late = g.add_plane(other, true);
  for (int k : {15, 25})
    g.add_plane_edge({k, seen_late, other.transformed(g.keyframes()[k].pose.inverse()), 50});
  std::vector<int> all;
  for (int k = 0; k < 30; ++k) all.push_back(k);
  const std::vector<Retirement> r =
      redundant_keyframes(g, all, KeyframeRetirementConfig{}, [](int) { return true; });
  std::vector<bool> leaves(30, false);
  for (const Retirement& x : r) leaves[x.keyframe] = true;
  for (int k = 0; k < 10; ++k) EXPECT_FALSE(leaves[k]) << k;  // no earlier pass
  EXPECT_FALSE(leaves[15]);                                   // saw a wall lap 1 did not
  EXPECT_TRUE(leaves[25]);                                    // that wall is held by 15, which stays
  EXPECT_FALSE(leaves[29]);                                   // the newest
  for (const Retirement& x : r) {
    EXPECT_FALSE(leaves[x.anchor]) << "keyframe " << x.keyframe << " anchored on " << x.anchor
                                   << ", which leaves too";
    if (x.keyframe >= 20 && x.keyframe != 25) {
      EXPECT_EQ(x.anchor, x.keyframe - 20);
    }
  }
  // Keyframe 25's anchor is 15: nearer than 5, and staying.
  for (const Retirement& x : r) {
    if (x.keyframe == 25) {
      EXPECT_EQ(x.anchor, 15);
    }
  }
  // What one call returns can be carried out in its order.
  for (const Retirement& x : r) EXPECT_NO_THROW(g.retire_keyframe(x.keyframe, x.anchor, kOdometry, kLoop));
}

TEST(KeyframeRetirement, TheEstimateMovesLittleAgainstKeepingEveryKeyframe) {
  const Scenario s = corridor_loop(true);
  const SituationalGraph kept = replay(s.graph, false);
  const SituationalGraph retired = replay(s.graph, true);
  const std::size_t n = kept.keyframes().size();
  EXPECT_EQ(kept.num_active_keyframes(), n);
  // The second lap left the graph but for the keyframes of the last window.
  EXPECT_LT(retired.num_active_keyframes(), n / 2 + 12);
  double max_kept = 0.0, max_kept_deg = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    if (retired.keyframes()[k].retired) continue;
    const Pose3 d = kept.keyframes()[k].pose.inverse() * retired.keyframes()[k].pose;
    max_kept = std::max(max_kept, d.translation().norm());
    max_kept_deg = std::max(max_kept_deg, Eigen::AngleAxisd(d.linear()).angle() / kDeg);
  }
  const double rmse_kept = position_rmse(kept, s.truth), rmse_retired = position_rmse(retired, s.truth);
  std::printf(
      "kept keyframes moved by at most %.4f m, %.3f deg; rmse against truth %.4f m (all kept) and %.4f m "
      "(retired)\n",
      max_kept, max_kept_deg, rmse_kept, rmse_retired);
  EXPECT_LT(max_kept, 0.03);
  EXPECT_LT(max_kept_deg, 0.3);
  EXPECT_LT(rmse_retired, rmse_kept + 0.02);
}
