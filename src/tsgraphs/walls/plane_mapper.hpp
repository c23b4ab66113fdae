#pragma once
/// Plane landmarks of the map: associating a keyframe's plane observations with mapped
/// planes (Mahalanobis distance of the plane difference plus a point-overlap check), and
/// finding duplicate landmarks of one face so they can be merged.
#include <cstdint>
#include <functional>
#include <unordered_map>
#include <unordered_set>
#include <map>
#include <utility>
#include <vector>

#include "tsgraphs/core/pose.hpp"
#include "tsgraphs/walls/plane_extraction.hpp"
#include "tsgraphs/core/config_fields.hpp"

namespace tsgraphs::walls {

struct PlaneMapperConfig {
  double sigma_angle_deg = 2.0;
  double sigma_distance = 0.05;
  double max_mahalanobis = 3.0;
  double overlap_distance = 0.5;
  double min_overlap_ratio = 0.05;
  double merge_angle_deg = 3.0;
  double merge_distance = 0.08;
  double merge_overlap_distance = 0.5;
  double landmark_voxel = 0.25;

  template <class V>
  void visit(V& v) {
    v("sigma_angle_deg", sigma_angle_deg, above(0.0, 90.0), "std of a plane's normal direction");
    v("sigma_distance", sigma_distance, above(0.0, 100.0), "m; std of a plane's offset");
    v("max_mahalanobis", max_mahalanobis, above(0.0, 1e6), "association gate on the Mahalanobis distance");
    v("overlap_distance", overlap_distance, between(0.01, 100.0),
      "m; an observed point this near a mapped point overlaps it");
    v("min_overlap_ratio", min_overlap_ratio, between(0.0, 1.0),
      "share of observed points that must overlap");
    v("merge_angle_deg", merge_angle_deg, between(0.0, 90.0), "duplicates: normals within this angle,");
    v("merge_distance", merge_distance, between(0.0, 100.0), "m; offsets within this,");
    v("merge_overlap_distance", merge_overlap_distance, between(0.01, 100.0),
      "m; and point sets within this of each other");
    v("landmark_voxel", landmark_voxel, between(0.01, 100.0),
      "m; a mapped plane's points are thinned to this");
  }
};

/// A mapped plane: its current value (set by the back-end) and the points seen on it.
struct PlaneLandmark {
  int id = -1;
  Plane plane;  ///< map frame, normal towards the observers
  bool vertical = true;
  /// Observations: keyframe id -> inlier points in that keyframe's frame.
  std::map<int, std::vector<Eigen::Vector3f>> observations;
  std::vector<Eigen::Vector3f> points;  ///< map frame, from observations and keyframe poses, downsampled
};

class PlaneMapper {
 public:
  explicit PlaneMapper(PlaneMapperConfig config = {});

  /// Id of the landmark `obs` (seen from a keyframe at T_map_keyframe) belongs to, or -1.
  /// Only landmarks of the same class (vertical/horizontal) and facing the same way match.
  int associate(const PlaneObservation& obs, const Pose3& T_map_keyframe) const;
  /// Creates landmark `id` from its first observation (plane set from it, in the map frame).
  void add_landmark(int id, const PlaneObservation& obs, const Pose3& T_map_keyframe, int keyframe_id);
  /// Records another observation of landmark `id`.
  void add_observation(int id, const PlaneObservation& obs, const Pose3& T_map_keyframe, int keyframe_id);
  /// After optimisation: sets each listed landmark's plane and rebuilds every point set from
  /// the keyframes' new poses.
  void update(const std::map<int, Plane>& planes, const std::function<Pose3(int)>& keyframe_pose);
  /// Pairs (keep, drop) of landmarks that are one face; keep is the one with more observations
  /// (the lower id on a tie). Landmarks linked by a chain of such pairs form one group with one
  /// keep, so every pair can be merged in turn; sorted by (keep, drop).
  std::vector<std::pair<int, int>> find_duplicates() const;
  /// Drops the observations of the keyframes `keyframe_ids`, in order (retired: earlier
  /// keyframes hold what they saw) and rebuilds each landmark they saw once, from the others; a
  /// landmark's only observation stays.
  void forget_keyframes(const std::vector<int>& keyframe_ids, const std::function<Pose3(int)>& keyframe_pose);
  /// Moves drop's observations into keep and removes drop.
  void merge(int keep, int drop, const std::function<Pose3(int)>& keyframe_pose);

  const std::map<int, PlaneLandmark>& landmarks() const { return landmarks_; }
  const PlaneMapperConfig& config() const { return config_; }

 private:
  /// Points hashed on cells of edge `radius`: whether any lies within radius of a point
  /// looks at 27 cells.
  class PointHash {
   public:
    PointHash(const std::vector<Eigen::Vector3f>& pts, double radius);
    void add(const Eigen::Vector3f& p);
    void clear() { cells_.clear(); }
    bool any_within(const Eigen::Vector3f& q) const;

   private:
    double inv_;
    float r2_;
    std::unordered_map<std::uint64_t, std::vector<Eigen::Vector3f>> cells_;
  };
  /// Per landmark: the voxels its points occupy and the keyframe poses they were placed with,
  /// so that adding an observation is cheap and update() redoes only landmarks that moved;
  /// and its points hashed at overlap_distance, kept with them: association asks every
  /// landmark in its gate, and hashing each one's points anew per observation was most of
  /// its cost.
  struct PointIndex {
    std::unordered_set<std::uint64_t> occupied;
    std::map<int, Pose3> poses;
    PointHash near;
  };
  void add_points(PlaneLandmark& lm, const std::vector<Eigen::Vector3f>& pts_keyframe,
                  const Pose3& T_map_keyframe, int keyframe_id);
  void rebuild(PlaneLandmark& lm, const std::function<Pose3(int)>& keyframe_pose);

  PlaneMapperConfig config_;
  std::map<int, PlaneLandmark> landmarks_;
  std::map<int, PointIndex> index_;
};

}  // namespace tsgraphs::walls
