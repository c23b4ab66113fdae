// Plane landmarks: association of observations (same face from several poses -> one
// landmark; the two faces of a thin wall, parallel walls, and collinear walls far apart ->
// never), duplicates found and merged, point sets rebuilt from moved keyframes without growing
// with revisits, and an office lap mapped from simulated scans with one landmark per face.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <map>
#include <numeric>
#include <set>
#include <string>
#include <unordered_map>
#include <vector>

#include "tsgraphs/pipeline/prefilter.hpp"
#include "tsgraphs/scene/builtin_scenes.hpp"
#include "tsgraphs/scene/scene_loader.hpp"
#include "tsgraphs/sim/simulator.hpp"
#include "tsgraphs/walls/plane_mapper.hpp"

using namespace tsgraphs;
using walls::PlaneExtractionConfig;
using walls::PlaneLandmark;
using walls::PlaneMapper;
using walls::PlaneMapperConfig;
using walls::PlaneObservation;

namespace {

constexpr double kDeg = M_PI / 180.0;
constexpr double kPrefilterVoxel = 0.1;  // the pipeline's default prefilter voxel (m)
constexpr double kSampleStep = 0.2;      // spacing of synthetic observation points (m)

// An observation of the vertical rectangle from `a` to `b` (map frame, 2-D ends), z in
// [0, height], seen from the keyframe at T_map_keyframe, as extraction would report it.
PlaneObservation observe_rectangle(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double height,
                                   const Pose3& T_map_keyframe) {
  PlaneObservation obs;
  const Pose3 T_keyframe_map = T_map_keyframe.inverse();
  const double length = (b - a).norm();
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (double s = 0.0; s <= length + 1e-9; s += kSampleStep) {
    for (double z = 0.0; z <= height + 1e-9; z += kSampleStep) {
      const Eigen::Vector2d xy = a + (b - a) * (s / length);
      const Eigen::Vector3d p = T_keyframe_map * Eigen::Vector3d(xy.x(), xy.y(), z);
      obs.points.push_back(p.cast<float>());
      sum += p;
    }
  }
  obs.num_inliers = static_cast<int>(obs.points.size());
  obs.centroid = sum / obs.num_inliers;
  const Eigen::Vector2d dir = (b - a).normalized();
  Eigen::Vector3d n = T_keyframe_map.linear() * Eigen::Vector3d(-dir.y(), dir.x(), 0.0);
  if (n.dot(obs.centroid) > 0.0) n = -n;  // towards the sensor
  obs.plane = Plane::from_point_normal(obs.centroid, n);
  obs.vertical = true;
  return obs;
}

Pose3 pose_at(double x, double y, double yaw = 0.0) { return make_pose(Eigen::Vector3d(x, y, 0.55), yaw); }

// Feeds one keyframe's observations to the mapper: associate or create. Returns the landmark
// id given to each observation.
std::vector<int> map_keyframe(PlaneMapper* mapper, const std::vector<PlaneObservation>& obs, const Pose3& T,
                              int kf, int* next_id) {
  std::vector<int> ids;
  for (const PlaneObservation& o : obs) {
    int id = mapper->associate(o, T);
    if (id < 0) {
      id = (*next_id)++;
      mapper->add_landmark(id, o, T, kf);
    } else {
      mapper->add_observation(id, o, T, kf);
    }
    ids.push_back(id);
  }
  return ids;
}

TEST(PlaneMapper, OneFaceFromSeveralPosesIsOneLandmark) {
  PlaneMapper mapper;
  int next_id = 0;
  // The face y = 4.9 of a wall along x in [0, 10], seen from six poses walking past it and
  // each seeing the part within 4 m.
  for (int kf = 0; kf < 6; ++kf) {
    const Pose3 T = pose_at(1.0 + 1.5 * kf, 2.0, 0.3 * kf);
    const double x0 = std::max(0.0, T.translation().x() - 4.0),
                 x1 = std::min(10.0, T.translation().x() + 4.0);
    const std::vector<int> ids =
        map_keyframe(&mapper, {observe_rectangle({x0, 4.9}, {x1, 4.9}, 2.9, T)}, T, kf, &next_id);
    EXPECT_EQ(ids[0], 0) << "keyframe " << kf;
  }
  ASSERT_EQ(mapper.landmarks().size(), 1u);
  const PlaneLandmark& lm = mapper.landmarks().at(0);
  EXPECT_EQ(lm.observations.size(), 6u);
  EXPECT_NEAR(lm.plane.n.dot(-Eigen::Vector3d::UnitY()), 1.0, 1e-9);  // towards the observers
  EXPECT_NEAR(lm.plane.d, 4.9, 1e-6);
}

TEST(PlaneMapper, TheTwoFacesOfAThinWallNeverAssociate) {
  PlaneMapper mapper;
  int next_id = 0;
  // A 0.1 m wall along y = 5, seen alternately from the south and the north side.
  for (int kf = 0; kf < 6; ++kf) {
    const bool south = kf % 2 == 0;
    const Pose3 T = pose_at(2.0 + 0.5 * kf, south ? 3.0 : 7.0);
    const double y = south ? 4.95 : 5.05;
    const std::vector<int> ids =
        map_keyframe(&mapper, {observe_rectangle({0.0, y}, {8.0, y}, 2.9, T)}, T, kf, &next_id);
    EXPECT_EQ(ids[0], south ? 0 : 1) << "keyframe " << kf;
  }
  ASSERT_EQ(mapper.landmarks().size(), 2u);
  EXPECT_LT(mapper.landmarks().at(0).plane.n.dot(mapper.landmarks().at(1).plane.n), -0.99);
  EXPECT_TRUE(mapper.find_duplicates().empty());
}

TEST(PlaneMapper, ParallelWallsHalfAMetreApartDoNotAssociate) {
  PlaneMapper mapper;
  const Pose3 T0 = pose_at(4.0, 2.0), T1 = pose_at(4.5, 2.2, 0.2);
  mapper.add_landmark(0, observe_rectangle({0.0, 5.0}, {8.0, 5.0}, 2.9, T0), T0, 0);
  // A wall 0.5 m behind, overlapping it in plan: the offset gate refuses it.
  const PlaneObservation behind = observe_rectangle({0.0, 5.5}, {8.0, 5.5}, 2.9, T1);
  EXPECT_EQ(mapper.associate(behind, T1), -1);
  // The same wall seen again (2 cm and 0.5 degrees off) does associate.
  Pose3 T1_off = T1;
  T1_off.translation().y() += 0.02;
  T1_off.linear() = T1.linear() * Eigen::AngleAxisd(0.5 * kDeg, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  EXPECT_EQ(mapper.associate(observe_rectangle({1.0, 5.0}, {7.0, 5.0}, 2.9, T1), T1_off), 0);
  mapper.add_landmark(1, behind, T1, 1);
  EXPECT_TRUE(mapper.find_duplicates().empty());
}

TEST(PlaneMapper, CollinearWallsFarApartDoNotAssociate) {
  PlaneMapper mapper;
  const Pose3 T0 = pose_at(2.0, 2.0), T1 = pose_at(14.0, 2.0);
  mapper.add_landmark(0, observe_rectangle({0.0, 5.0}, {4.0, 5.0}, 2.9, T0), T0, 0);
  // Same plane, 8 m further along: the plane gate passes, the overlap check refuses.
  const PlaneObservation far = observe_rectangle({12.0, 5.0}, {16.0, 5.0}, 2.9, T1);
  EXPECT_EQ(mapper.associate(far, T1), -1);
  mapper.add_landmark(1, far, T1, 1);
  EXPECT_TRUE(mapper.find_duplicates().empty());
  // Across a 1 m door the overlap check passes (points within overlap_distance of each other).
  const PlaneObservation beyond_door = observe_rectangle({4.4, 5.0}, {8.0, 5.0}, 2.9, T1);
  EXPECT_EQ(mapper.associate(beyond_door, T1), 0);
}

TEST(PlaneMapper, FarFromTheOriginTheOffsetIsComparedAtTheObservation) {
  // A wall 300 m from the map origin; the keyframe's heading is off by 1 degree, which changes
  // the raw d by 300 m * sin(1 deg) = 5 m but the plane at the observation by almost nothing.
  PlaneMapper mapper;
  const Pose3 T0 = pose_at(300.0, 2.0);
  mapper.add_landmark(0, observe_rectangle({296.0, 4.9}, {304.0, 4.9}, 2.9, T0), T0, 0);
  const Pose3 T1 = pose_at(301.0, 2.0);
  Pose3 T1_off = T1;
  T1_off.linear() = Eigen::AngleAxisd(1.0 * kDeg, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const PlaneObservation obs = observe_rectangle({298.0, 4.9}, {304.0, 4.9}, 2.9, T1);
  EXPECT_GT(std::abs(obs.plane.transformed(T1_off).d - mapper.landmarks().at(0).plane.d), 4.0);
  EXPECT_EQ(mapper.associate(obs, T1_off), 0);
}

TEST(PlaneMapper, OnlyTheSameClassAssociates) {
  PlaneMapper mapper;
  const Pose3 T = pose_at(2.0, 2.0);
  PlaneObservation wall = observe_rectangle({0.0, 4.9}, {4.0, 4.9}, 2.9, T);
  mapper.add_landmark(0, wall, T, 0);
  wall.vertical = false;  // the same numbers labelled as a floor/ceiling plane
  EXPECT_EQ(mapper.associate(wall, T), -1);
}

TEST(PlaneMapper, DuplicatesAreFoundAndMerged) {
  PlaneMapper mapper;
  const Pose3 T0 = pose_at(2.0, 2.0), T1 = pose_at(6.0, 2.5, 0.4), T2 = pose_at(3.0, 2.0);
  // Landmarks 0 and 1: one face seen 1 cm and 0.5 degrees apart (made apart, as after a drift).
  mapper.add_landmark(0, observe_rectangle({0.0, 4.9}, {4.5, 4.9}, 2.9, T0), T0, 0);
  mapper.add_observation(0, observe_rectangle({0.0, 4.9}, {5.0, 4.9}, 2.9, T2), T2, 2);
  Pose3 T1_off = T1;
  T1_off.translation().y() += 0.01;
  T1_off.linear() = T1.linear() * Eigen::AngleAxisd(0.5 * kDeg, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  mapper.add_landmark(1, observe_rectangle({4.0, 4.9}, {9.0, 4.9}, 2.9, T1), T1_off, 1);
  // Not duplicates of them: the far face of the wall, a wall 0.5 m behind, and a collinear
  // wall 3 m away.
  const Pose3 T3 = pose_at(4.0, 8.0);
  mapper.add_landmark(2, observe_rectangle({0.0, 5.1}, {8.0, 5.1}, 2.9, T3), T3, 3);
  mapper.add_landmark(3, observe_rectangle({0.0, 5.4}, {8.0, 5.4}, 2.9, T0), T0, 4);
  mapper.add_landmark(4, observe_rectangle({12.0, 4.9}, {16.0, 4.9}, 2.9, T1), T1, 5);

  const std::vector<std::pair<int, int>> dups = mapper.find_duplicates();
  ASSERT_EQ(dups.size(), 1u);
  EXPECT_EQ(dups[0], std::make_pair(0, 1));  // 0 has more observations

  const std::map<int, Pose3> poses = {{0, T0}, {1, T1_off}, {2, T2}, {3, T3}, {4, T0}, {5, T1}};
  const auto pose_of = [&](int kf) { return poses.at(kf); };
  const std::size_t points_before = mapper.landmarks().at(0).points.size();
  mapper.merge(0, 1, pose_of);
  ASSERT_EQ(mapper.landmarks().count(1), 0u);
  const PlaneLandmark& kept = mapper.landmarks().at(0);
  EXPECT_EQ(kept.observations.size(), 3u);
  EXPECT_EQ(kept.observations.count(1), 1u);
  EXPECT_GT(kept.points.size(), points_before);  // it now reaches x = 9
  float max_x = 0.0f;
  for (const Eigen::Vector3f& p : kept.points) max_x = std::max(max_x, p.x());
  EXPECT_GT(max_x, 8.5f);
  EXPECT_TRUE(mapper.find_duplicates().empty());
}

TEST(PlaneMapper, UpdateMovesPointsWithKeyframesAndRevisitsDoNotGrowThem) {
  PlaneMapper mapper;
  const Pose3 T0 = pose_at(2.0, 2.0);
  const PlaneObservation obs = observe_rectangle({0.0, 4.9}, {4.0, 4.9}, 2.9, T0);
  mapper.add_landmark(0, obs, T0, 0);
  const std::size_t first = mapper.landmarks().at(0).points.size();
  const double voxel = mapper.config().landmark_voxel;
  // One point per landmark voxel: the 4 m x 2.9 m face at 0.25 m holds at most 17 x 13 x 2.
  EXPECT_LE(first, static_cast<std::size_t>((4.0 / voxel + 1) * (2.9 / voxel + 1) * 2));
  for (int kf = 1; kf < 30; ++kf) mapper.add_observation(0, obs, T0, kf);
  EXPECT_EQ(mapper.landmarks().at(0).points.size(), first);

  // After optimisation every keyframe turns out 1 m further east and the plane is set anew.
  Pose3 moved = T0;
  moved.translation().x() += 1.0;
  Plane plane = mapper.landmarks().at(0).plane;
  plane.d += 0.01;
  mapper.update({{0, plane}}, [&](int) { return moved; });
  const PlaneLandmark& lm = mapper.landmarks().at(0);
  EXPECT_EQ(lm.plane.d, plane.d);
  EXPECT_LE(lm.points.size(), first + first / 2);
  float min_x = 1e9f, max_x = -1e9f;
  for (const Eigen::Vector3f& p : lm.points) {
    min_x = std::min(min_x, p.x());
    max_x = std::max(max_x, p.x());
  }
  EXPECT_NEAR(min_x, 1.0f, voxel);
  EXPECT_NEAR(max_x, 5.0f, voxel);
}

TEST(PlaneMapper, AssociationOverlapsTheLandmarksPointsWhereTheyAreNow) {
  // The overlap test reads each landmark's points hashed once and kept beside them: a landmark
  // moved by update() is overlapped where it is now, not where it was mapped.
  PlaneMapper mapper;
  const Pose3 T0 = pose_at(2.0, 2.0);
  mapper.add_landmark(0, observe_rectangle({0.0, 4.9}, {4.0, 4.9}, 2.9, T0), T0, 0);
  const PlaneObservation west = observe_rectangle({0.0, 4.9}, {2.0, 4.9}, 2.9, T0);
  const PlaneObservation east = observe_rectangle({5.5, 4.9}, {6.5, 4.9}, 2.9, T0);
  EXPECT_EQ(mapper.associate(west, T0), 0);
  EXPECT_EQ(mapper.associate(east, T0), -1);  // 1.5 m beyond the face's end

  // The keyframe turns out 3 m further east: the face now spans x 3..7.
  Pose3 moved = T0;
  moved.translation().x() += 3.0;
  mapper.update({}, [&](int) { return moved; });
  EXPECT_EQ(mapper.associate(west, T0), -1);  // 1 m short of the face's new west end
  EXPECT_EQ(mapper.associate(east, T0), 0);

  // And so after a merge, which rebuilds the kept landmark from both.
  mapper.add_landmark(1, observe_rectangle({-6.0, 4.9}, {-4.0, 4.9}, 2.9, T0), T0, 1);
  const PlaneObservation far_west = observe_rectangle({-3.0, 4.9}, {-2.0, 4.9}, 2.9, T0);
  EXPECT_EQ(mapper.associate(far_west, T0), -1);
  mapper.merge(0, 1, [&](int kf) { return kf == 0 ? moved : T0; });
  EXPECT_EQ(mapper.associate(far_west, T0), -1);
  EXPECT_EQ(mapper.associate(observe_rectangle({-5.0, 4.9}, {-4.5, 4.9}, 2.9, T0), T0), 0);
  EXPECT_EQ(mapper.associate(east, T0), 0);
}

TEST(PlaneMapper, ARetiredKeyframesObservationsAreForgottenButALandmarksLastStays) {
  PlaneMapper mapper;
  const Pose3 T0 = pose_at(2.0, 2.0), T1 = pose_at(6.0, 2.0);
  // Keyframe 0 saw the west half of the face, keyframe 1 the east half, keyframe 2 a face of its own.
  mapper.add_landmark(0, observe_rectangle({0.0, 4.9}, {4.0, 4.9}, 2.9, T0), T0, 0);
  mapper.add_observation(0, observe_rectangle({4.0, 4.9}, {8.0, 4.9}, 2.9, T1), T1, 1);
  mapper.add_landmark(1, observe_rectangle({0.0, -1.0}, {4.0, -1.0}, 2.9, T1), T1, 2);
  const std::map<int, Pose3> poses{{0, T0}, {1, T1}, {2, T1}};
  const auto pose_of = [&](int k) { return poses.at(k); };
  const auto max_x = [&](int id) {
    float x = -1e9f;
    for (const Eigen::Vector3f& p : mapper.landmarks().at(id).points) x = std::max(x, p.x());
    return x;
  };
  EXPECT_NEAR(max_x(0), 8.0f, 0.25f);
  PlaneMapper both = mapper;
  mapper.forget_keyframes({1}, pose_of);
  EXPECT_EQ(mapper.landmarks().at(0).observations.count(1), 0u);
  EXPECT_NEAR(max_x(0), 4.0f, 0.25f);  // the east half went with its keyframe
  mapper.forget_keyframes({2}, pose_of);
  EXPECT_EQ(mapper.landmarks().at(1).observations.size(), 1u);  // its only observation stays
  EXPECT_FALSE(mapper.landmarks().at(1).points.empty());

  // Keyframes forgotten together go in order: of landmark 0's two, the later one stays.
  both.forget_keyframes({0, 1, 2}, pose_of);
  ASSERT_EQ(both.landmarks().at(0).observations.size(), 1u);
  EXPECT_EQ(both.landmarks().at(0).observations.count(1), 1u);
  float min_x = 1e9f;
  for (const Eigen::Vector3f& p : both.landmarks().at(0).points) min_x = std::min(min_x, p.x());
  EXPECT_NEAR(min_x, 4.0f, 0.25f);  // rebuilt from keyframe 1's east half alone
  EXPECT_EQ(both.landmarks().at(1).observations.size(), 1u);
}

// ---- An office lap from simulated scans, scored against the scene's wall faces ----

// The pipeline's own prefilter (NaN drop, range crop, one centroid per voxel).
PointCloud voxel_filter(const PointCloud& in, double voxel) {
  pipeline::PrefilterConfig config;
  config.voxel_size = voxel;
  return pipeline::prefilter(in, config);
}

// A piece of one side of a wall, between the walls that abut it (a partition between two
// rooms cuts the face of the wall it meets into two pieces) and its doors: its plane (normal
// out of the wall) and the part of the plane it covers.
struct TrueFace {
  Plane plane;
  Eigen::Vector2d origin, along;
  double s0 = 0.0, s1 = 0.0, z0 = 0.0, z1 = 0.0;
  double s_of(const Eigen::Vector3d& p) const { return along.dot(p.head<2>() - origin); }
  bool contains(const Eigen::Vector3d& p, double margin) const {
    const double s = s_of(p);
    return std::abs(plane.signed_distance(p)) <= margin && s >= s0 - margin && s <= s1 + margin &&
           p.z() >= z0 - margin && p.z() <= z1 + margin;
  }
};

std::vector<TrueFace> wall_faces(const scene::Scene& scene) {
  std::vector<TrueFace> faces;
  for (const scene::Wall& w : scene.walls) {
    const Eigen::Vector2d dir = (w.to - w.from).normalized();
    const Eigen::Vector2d side(-dir.y(), dir.x());
    for (const double sign : {1.0, -1.0}) {
      TrueFace f;
      f.origin = w.from + sign * 0.5 * w.thickness * side;
      f.along = dir;
      f.z0 = scene.levels[w.level].elevation;
      f.z1 = f.z0 + w.height;
      f.plane = Plane::from_point_normal(Eigen::Vector3d(f.origin.x(), f.origin.y(), f.z0),
                                         Eigen::Vector3d(sign * side.x(), sign * side.y(), 0.0));
      // Cut where another wall's end stands on this face.
      std::vector<double> cuts = {w.joined_from ? -0.5 * w.thickness : 0.0,
                                  (w.to - w.from).norm() + (w.joined_to ? 0.5 * w.thickness : 0.0)};
      for (const scene::Wall& other : scene.walls) {
        for (const Eigen::Vector2d& e : {other.from, other.to}) {
          const Eigen::Vector3d e3(e.x(), e.y(), f.z0);
          const double s = f.s_of(e3);
          if (&other != &w && std::abs(f.plane.signed_distance(e3)) <= 0.5 * w.thickness + 1e-6 &&
              s > cuts[0] && s < cuts[1]) {
            cuts.push_back(s);
          }
        }
      }
      // A door cuts it too: the lintel above is out of sight of a sensor 0.55 m above the floor
      // unless it is far from the wall, so the two sides are seen apart.
      for (const scene::Opening& o : w.openings) {
        if (o.sill == 0.0) {
          cuts.push_back(o.at - 0.5 * o.width);
          cuts.push_back(o.at + 0.5 * o.width);
        }
      }
      std::sort(cuts.begin(), cuts.end());
      for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
        f.s0 = cuts[i];
        f.s1 = cuts[i + 1];
        faces.push_back(f);
      }
    }
  }
  return faces;
}

// How many of `pts` (map frame) lie on each face that faces like `n`.
std::vector<std::size_t> points_on_faces(const std::vector<TrueFace>& faces,
                                         const std::vector<Eigen::Vector3f>& pts, const Eigen::Vector3d& n) {
  constexpr double kMargin = 0.1;
  std::vector<std::size_t> on(faces.size(), 0);
  for (std::size_t f = 0; f < faces.size(); ++f) {
    if (faces[f].plane.n.dot(n) < std::cos(10.0 * kDeg)) continue;
    on[f] = std::count_if(pts.begin(), pts.end(), [&](const Eigen::Vector3f& p) {
      return faces[f].contains(p.cast<double>(), kMargin);
    });
  }
  return on;
}

bool coplanar(const TrueFace& a, const TrueFace& b) {
  return a.plane.n.dot(b.plane.n) > std::cos(1.0 * kDeg) && std::abs(a.plane.d - b.plane.d) < 0.05;
}

TEST(PlaneMapper, OfficeLapFromTruePosesGivesOneLandmarkPerFace) {
  const scene::Scene scene = scene::parse_scene(*scene::builtin_scene_text("office"), "builtin:office", ".");
  const sim::Simulator sim(scene, 3);
  const std::vector<TrueFace> faces = wall_faces(scene);
  constexpr std::size_t kKeyframeStep = 15;  // scans between keyframes: 1.5 m at 1 m/s
  const std::size_t lap = sim.num_scans() / 2;

  PlaneMapper mapper;
  int next_id = 0, kf = 0, observations = 0;
  std::map<int, Pose3> poses;
  for (std::size_t k = 0; k < lap; k += kKeyframeStep, ++kf) {
    const Pose3& T = sim.true_poses()[k];
    poses[kf] = T;
    const std::vector<PlaneObservation> obs = walls::extract_planes(
        voxel_filter(sim.scan(k), kPrefilterVoxel), T.linear(), PlaneExtractionConfig{});
    observations += static_cast<int>(obs.size());
    map_keyframe(&mapper, obs, T, kf, &next_id);
  }
  const std::size_t before_merge = mapper.landmarks().size();
  const auto pose_of = [&](int id) { return poses.at(id); };
  int merged = 0;
  for (const auto& [keep, drop] : mapper.find_duplicates()) {
    mapper.merge(keep, drop, pose_of);
    ++merged;
  }

  // Wall landmarks (most of their points on wall faces): every observation on faces of one
  // plane; no face piece shared by two landmarks; planes close to the truth.
  constexpr double kMinShare = 0.1;  // a landmark is on a face piece if this share of its points is
  std::map<int, std::set<int>> landmarks_of_face;
  int wall_landmarks = 0, impure = 0;
  double max_angle = 0.0, max_offset = 0.0;
  for (const auto& [id, lm] : mapper.landmarks()) {
    if (!lm.vertical) continue;
    const std::vector<std::size_t> on = points_on_faces(faces, lm.points, lm.plane.n);
    const std::size_t main_face = std::max_element(on.begin(), on.end()) - on.begin();
    if (2 * on[main_face] < lm.points.size() &&
        2 * std::accumulate(on.begin(), on.end(), std::size_t{0}) < lm.points.size()) {
      continue;  // furniture
    }
    ++wall_landmarks;
    const TrueFace& truth = faces[main_face];
    for (std::size_t f = 0; f < faces.size(); ++f) {
      if (on[f] < kMinShare * lm.points.size()) continue;
      landmarks_of_face[static_cast<int>(f)].insert(id);
      if (!coplanar(faces[f], truth)) {
        ++impure;
        std::printf("  landmark %d: on face %zu and face %zu\n", id, f, main_face);
      }
    }
    for (const auto& [k, pts] : lm.observations) {
      std::vector<Eigen::Vector3f> world;
      for (const Eigen::Vector3f& p : pts) world.push_back((poses.at(k) * p.cast<double>()).cast<float>());
      const std::vector<std::size_t> seen = points_on_faces(faces, world, lm.plane.n);
      std::size_t on_plane = 0;
      for (std::size_t f = 0; f < faces.size(); ++f) on_plane += coplanar(faces[f], truth) ? seen[f] : 0;
      if (2 * on_plane < world.size()) {
        ++impure;
        std::printf("  landmark %d: keyframe %d saw another plane than face %zu's\n", id, k, main_face);
      }
    }
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3f& p : lm.points) centroid += p.cast<double>();
    centroid /= static_cast<double>(lm.points.size());
    const Plane& plane = truth.plane;
    max_angle =
        std::max(max_angle, std::atan2(lm.plane.n.cross(plane.n).norm(), lm.plane.n.dot(plane.n)) / kDeg);
    max_offset = std::max(max_offset, std::abs(plane.signed_distance(centroid)));
  }
  int faces_with_several = 0;
  for (const auto& [f, ids] : landmarks_of_face) {
    if (ids.size() > 1) {
      ++faces_with_several;
      std::printf("  face %d (n %.1f %.1f, d %.2f, s %.2f..%.2f) has %zu landmarks:", f, faces[f].plane.n.x(),
                  faces[f].plane.n.y(), faces[f].plane.d, faces[f].s0, faces[f].s1, ids.size());
      for (const int id : ids) {
        const auto on =
            points_on_faces(faces, mapper.landmarks().at(id).points, mapper.landmarks().at(id).plane.n);
        std::printf(" %d (%zu of %zu points)", id, on[f], mapper.landmarks().at(id).points.size());
      }
      std::printf("\n");
    }
  }
  std::printf(
      "[office lap] %d keyframes, %d observations -> %zu landmarks, %d merged as duplicates, %zu left; "
      "%d on %zu of %zu wall face pieces, %d impure, %d pieces with several; plane error max %.3f deg, %.4f "
      "m\n",
      kf, observations, before_merge, merged, mapper.landmarks().size(), wall_landmarks,
      landmarks_of_face.size(), faces.size(), impure, faces_with_several, max_angle, max_offset);
  EXPECT_GE(landmarks_of_face.size(), 20u);
  EXPECT_EQ(impure, 0);
  EXPECT_EQ(faces_with_several, 0);
  EXPECT_LE(max_angle, 0.5);
  EXPECT_LE(max_offset, 0.02);
}

}  // namespace
