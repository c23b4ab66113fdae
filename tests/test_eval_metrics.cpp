// Trajectory and wall figures of docs/metrics.md, and metrics.json's shape.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "tsgraphs/eval/metrics.hpp"
#include "tsgraphs/eval/trajectory_metrics.hpp"
#include "tsgraphs/eval/wall_metrics.hpp"
#include "tsgraphs/scene/scene_loader.hpp"

using namespace tsgraphs;
using namespace tsgraphs::eval;

TEST(TrajectoryMetrics, AteLoopIsTheGapBetweenFirstAndLast) {
  std::vector<Pose3> est = {make_pose({0, 0, 0}, 0), make_pose({5, 5, 0}, 1), make_pose({0.3, 0.4, 0}, 0)};
  EXPECT_NEAR(ate_loop(est), 0.5, 1e-12);
  EXPECT_EQ(ate_loop({}), 0.0);
}

TEST(TrajectoryMetrics, AteRmseAlignsTheFirstPose) {
  // The estimate is the truth seen from another frame (rotated and shifted): zero error.
  std::vector<Pose3> truth, est;
  const Pose3 other = make_pose({3, -2, 1}, 0.7);
  for (int i = 0; i < 10; ++i) {
    truth.push_back(make_pose({i * 1.0, 0.5 * i, 0}, 0.1 * i));
    est.push_back(other * truth.back());
  }
  EXPECT_NEAR(ate_rmse(est, truth), 0.0, 1e-9);
  // A constant 0.3 m offset after the first pose gives an RMSE of 0.3 * sqrt(9/10).
  for (int i = 1; i < 10; ++i) est[i].translation() += other.linear() * Eigen::Vector3d(0.3, 0, 0);
  EXPECT_NEAR(ate_rmse(est, truth), 0.3 * std::sqrt(0.9), 1e-9);
  EXPECT_THROW(ate_rmse(est, {truth[0]}), std::invalid_argument);
}

TEST(TrajectoryMetrics, SegmentDriftIsTheRelativeErrorOverEachLength) {
  // A straight 10 m walk, 1 m a pose, whose estimate is 10 % short: every segment is 10 % off,
  // wherever it starts and whatever frame the estimate is in.
  std::vector<Pose3> truth, est;
  const Pose3 other = make_pose({3, -2, 1}, 0.7);
  for (int i = 0; i <= 10; ++i) {
    truth.push_back(make_pose({i * 1.0, 0, 0}, 0.0));
    est.push_back(other * make_pose({i * 0.9, 0, 0}, 0.0));
  }
  EXPECT_NEAR(segment_drift(est, truth, {2.0, 5.0}), 0.1, 1e-9);
  // A 1 m jump between poses 4 and 5 counts in the segments across it only: of the 2 m ones
  // (starts 0-8), the two that span it are 1 m off (0.5 of their length), the rest none.
  std::vector<Pose3> jump = truth;
  for (int i = 5; i <= 10; ++i) jump[i].translation().y() += 1.0;
  EXPECT_NEAR(segment_drift(jump, truth, {2.0}), 2 * 0.5 / 9.0, 1e-9);
  EXPECT_EQ(segment_drift(est, truth, {20.0}), -1.0);  // longer than the path
  EXPECT_THROW(segment_drift(est, {truth[0]}, {2.0}), std::invalid_argument);
}

namespace {

const char* kScene = R"(
name: two_rooms
sensor: {preset: vlp-16, mount_height: 0.5}
levels:
  - {name: L0, elevation: 0.0, ceiling: 2.8, slab: [[0, 0], [10, 0], [10, 5], [0, 5]]}
walls:
  - {level: L0, from: [0, 0], to: [10, 0], thickness: 0.2, height: 2.8}
  - {level: L0, from: [5, 0], to: [5, 5], thickness: 0.2, height: 2.8}
trajectory:
  level: L0
  speed: 1.0
  waypoints: [[1, 2], [4, 2]]
)";

}  // namespace

TEST(WallMetrics, FacesOfAWallAreItsTwoSidesFacingOut) {
  const scene::Scene scene = scene::parse_scene(kScene, "two_rooms.yaml", ".");
  const auto faces = wall_faces(scene);
  // Wall 1 ends on the north side of wall 0 at x = 5: that side is two faces, its south side one.
  ASSERT_EQ(faces.size(), 5u);
  // Wall 0 runs along x at y = 0, 0.2 thick: faces at y = +0.1 (normal +y) and y = -0.1 (normal -y).
  EXPECT_NEAR(faces[0].plane.signed_distance({3, 0.1, 1}), 0.0, 1e-12);
  EXPECT_NEAR(faces[0].plane.n.y(), 1.0, 1e-12);
  EXPECT_NEAR(faces[0].a.x(), 0.0, 1e-12);
  EXPECT_NEAR(faces[0].b.x(), 4.9, 1e-12);
  EXPECT_NEAR(faces[1].a.x(), 5.1, 1e-12);
  EXPECT_NEAR(faces[1].b.x(), 10.0, 1e-12);
  EXPECT_NEAR(faces[2].plane.signed_distance({3, -0.1, 1}), 0.0, 1e-12);
  EXPECT_NEAR(faces[2].plane.n.y(), -1.0, 1e-12);
  EXPECT_NEAR(faces[2].b.x() - faces[2].a.x(), 10.0, 1e-12);
  EXPECT_NEAR(faces[0].z1 - faces[0].z0, 2.8, 1e-12);
}

TEST(WallMetrics, ErrorsOfMappedPlanesAndDuplicates) {
  const scene::Scene scene = scene::parse_scene(kScene, "two_rooms.yaml", ".");
  const auto faces = wall_faces(scene);
  // Wall points seen on face 0 (y = 0.1) from a sensor at (2, 2, 0.5).
  PointCloud scan;
  for (int i = 0; i < 200; ++i) {
    scan.points.emplace_back(0.5f + 0.01f * i, 0.1f - 2.0f,
                             0.5f);  // sensor frame = world shifted by (2, 2, 0)
    scan.labels.push_back(static_cast<std::uint32_t>(PointLabel::kWall));
  }
  const Pose3 sensor = make_pose({2, 2, 0}, 0.0);
  WallMetricsConfig cfg;
  std::vector<FaceHits> hits;
  count_face_hits(faces, scan, sensor, cfg, &hits);
  ASSERT_EQ(hits.size(), faces.size());
  EXPECT_EQ(hits[0].count, 200);  // x 2.5 .. 4.49: the face west of the junction
  EXPECT_EQ(hits[2].count, 0);    // the far side is not visible from the sensor

  // A mapped plane 2 cm off and tilted by 0.5 degrees; a second one covering the same stretch.
  const double tilt = 0.5 * M_PI / 180.0;
  MappedWall m;
  m.id = 7;
  m.plane = Plane::from_point_normal({3.5, 0.12, 0}, {std::sin(tilt), std::cos(tilt), 0});
  m.a = {0, 0.12};
  m.b = {5, 0.12};
  m.z0 = 0.2;
  m.z1 = 2.5;
  std::vector<MappedWall> mapped = {m};
  WallErrors e = wall_errors(faces, hits, mapped, Pose3::Identity(), cfg);
  EXPECT_EQ(e.n_faces_seen, 1);
  EXPECT_EQ(e.n_faces_mapped, 1);
  EXPECT_NEAR(e.mean_dist_err, 0.02, 1e-3);
  EXPECT_NEAR(e.mean_angle_err_deg, 0.5, 1e-6);
  EXPECT_EQ(e.n_duplicates, 0);
  MappedWall dup = m;
  dup.id = 8;
  dup.plane = Plane::from_point_normal({3, 0.15, 0}, {0, 1, 0});
  mapped.push_back(dup);
  e = wall_errors(faces, hits, mapped, Pose3::Identity(), cfg);
  EXPECT_EQ(e.n_duplicates, 1);
  EXPECT_NEAR(e.mean_dist_err, 0.02, 1e-3);  // the closer plane is the associated one
  // A plane facing the other way is not this face's.
  mapped = {m};
  mapped[0].plane = Plane::from_point_normal({3, 0.1, 0}, {0, -1, 0});
  EXPECT_EQ(wall_errors(faces, hits, mapped, Pose3::Identity(), cfg).n_faces_mapped, 0);
}

TEST(Metrics, JsonHasEveryKeyAndNullsForMissingFigures) {
  Metrics m;
  m.trajectory.ate_loop = 0.05;
  const auto j = nlohmann::json::parse(metrics_json(m));
  for (const char* section : {"consistency", "trajectory", "pgo", "rooms_gt", "ground", "walls", "speed"})
    ASSERT_TRUE(j.contains(section)) << section;
  for (const char* key : {"N1st", "N2nd", "N_re", "f_re", "dcs", "d_center"})
    EXPECT_TRUE(j["consistency"].contains(key) && j["consistency"][key].is_null()) << key;
  EXPECT_DOUBLE_EQ(j["trajectory"]["ate_loop"].get<double>(), 0.05);
  EXPECT_TRUE(j["trajectory"]["ate_rmse"].is_null());
  for (const char* key : {"t_pgo_s", "n_optimisations", "n_variables", "n_factors"})
    EXPECT_TRUE(j["pgo"].contains(key));
  for (const char* key : {"precision", "recall", "f1", "mean_iou", "under_segmented", "over_segmented",
                          "n_rooms_final", "unsupported", "unsupported_fraction_max", "ipa_precision_micro",
                          "ipa_recall_micro", "ipa_precision_macro", "ipa_recall_macro"})
    EXPECT_TRUE(j["rooms_gt"].contains(key) && j["rooms_gt"][key].is_null()) << key;
  for (const char* key : {"mean_dist_err", "mean_angle_err_deg"}) EXPECT_TRUE(j["walls"].contains(key));
  for (const char* key : {"rtf", "frontend_ms_mean", "frontend_ms_p95", "peak_rss_mb"})
    EXPECT_TRUE(j["speed"].contains(key));
}
