// GCC 12 reports false -Warray-bounds in Eigen's SSE loads of Vector3f, inlined from PCL's
// ICP base (Umeyama); the code is Eigen's and PCL's, not ours. Set before any Eigen header.
#pragma GCC diagnostic ignored "-Warray-bounds"
#include "tsgraphs/registration/registration.hpp"

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/registration/gicp.h>
#include <pcl/search/kdtree.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "tsgraphs/core/voxel_grid.hpp"

namespace tsgraphs::registration {
namespace {

using PclPoint = pcl::PointXYZ;
using PclCloud = pcl::PointCloud<PclPoint>;
using KdTree = pcl::search::KdTree<PclPoint>;

// A point's covariance needs at least this many neighbours to be a 3-D spread (GICP).
constexpr int kMinCovarianceNeighbours = 3;

void check_config(const RegistrationConfig& c) {
  const auto fail = [](const std::string& what) {
    throw std::invalid_argument("RegistrationConfig: " + what);
  };
  if (!(c.voxel_size >= 0.0) || !std::isfinite(c.voxel_size)) fail("voxel_size must be >= 0");
  if (!(c.max_correspondence_distance > 0.0)) fail("max_correspondence_distance must be > 0");
  if (!(c.fine_correspondence_distance >= 0.0)) fail("fine_correspondence_distance must be >= 0");
  if (c.max_iterations < 1) fail("max_iterations must be >= 1");
  if (c.k_correspondences < kMinCovarianceNeighbours) fail("k_correspondences must be >= 3");
  if (!(c.transformation_epsilon > 0.0)) fail("transformation_epsilon must be > 0");
  if (!(c.fitness_distance > 0.0)) fail("fitness_distance must be > 0");
}

/// The finite points of `cloud`, each voxel of edge `voxel_size` replaced by the centroid of
/// its points (0: every finite point), as a PCL cloud.
PclCloud::Ptr downsample(const PointCloud& cloud, double voxel_size) {
  auto out = pcl::make_shared<PclCloud>();
  for (const Eigen::Vector3f& p : voxel_downsample(cloud, voxel_size).points) out->push_back(PclPoint(p.x(), p.y(), p.z()));
  return out;
}

struct Fitness {
  double mean_squared = 0.0;
  double inlier_ratio = 0.0;
};

/// Nearest target point of every transformed source point: mean squared distance over the
/// pairs closer than `max_distance`, and their share. No inlier gives the worst mean an
/// inlier could have, max_distance^2.
Fitness measure_fitness(const PclCloud& source, const Eigen::Matrix4f& T, const KdTree& target_tree,
                        double max_distance) {
  const double max_sq = max_distance * max_distance;
  pcl::Indices index(1);
  std::vector<float> dist_sq(1);
  double sum = 0.0;
  std::size_t inliers = 0;
  for (const PclPoint& p : source.points) {
    PclPoint q;
    q.getVector4fMap() = T * p.getVector4fMap();
    if (target_tree.nearestKSearch(q, 1, index, dist_sq) < 1) continue;
    if (dist_sq[0] <= max_sq) {
      sum += dist_sq[0];
      ++inliers;
    }
  }
  Fitness f;
  f.mean_squared = inliers > 0 ? sum / static_cast<double>(inliers) : max_sq;
  f.inlier_ratio = source.empty() ? 0.0 : static_cast<double>(inliers) / static_cast<double>(source.size());
  return f;
}

}  // namespace

RegistrationResult register_clouds(const PointCloud& source, const PointCloud& target, const Pose3& initial_guess,
                                   const RegistrationConfig& config) {
  check_config(config);
  RegistrationResult result;
  result.T_target_source = initial_guess;
  result.fitness = config.fitness_distance * config.fitness_distance;
  if (!initial_guess.matrix().allFinite()) return result;

  const PclCloud::Ptr src = downsample(source, config.voxel_size);
  const PclCloud::Ptr tgt = downsample(target, config.voxel_size);
  // GICP's covariances read k neighbours of every point: smaller clouds cannot be matched.
  const std::size_t min_points = static_cast<std::size_t>(config.k_correspondences);
  if (src->size() < min_points || tgt->size() < min_points) return result;

  // One target tree serves GICP's correspondences and the fitness measure.
  auto tree = pcl::make_shared<KdTree>();
  tree->setInputCloud(tgt);

  pcl::GeneralizedIterativeClosestPoint<PclPoint, PclPoint> gicp;
  gicp.setMaxCorrespondenceDistance(config.max_correspondence_distance);
  gicp.setMaximumIterations(config.max_iterations);
  gicp.setCorrespondenceRandomness(config.k_correspondences);
  // The same bound on every element of the transform's change, rotation and translation.
  gicp.setTransformationEpsilon(config.transformation_epsilon);
  gicp.setRotationEpsilon(config.transformation_epsilon);
  gicp.setInputSource(src);
  gicp.setInputTarget(tgt);
  gicp.setSearchMethodTarget(tree, true);

  PclCloud aligned;
  gicp.align(aligned, initial_guess.matrix().cast<float>());
  Eigen::Matrix4f T = gicp.getFinalTransformation();
  if (!gicp.hasConverged() || !T.allFinite()) return result;
  if (config.fine_correspondence_distance > 0.0 &&
      config.fine_correspondence_distance < config.max_correspondence_distance) {
    // Same clouds, trees and covariances: only the gate changes.
    gicp.setMaxCorrespondenceDistance(config.fine_correspondence_distance);
    gicp.align(aligned, T);
    T = gicp.getFinalTransformation();
    if (!gicp.hasConverged() || !T.allFinite()) return result;
  }

  Pose3 estimate = Pose3::Identity();
  const Eigen::Matrix4d Td = T.cast<double>();
  // Re-orthonormalise: the float product of GICP's increments drifts off SO(3) slightly.
  estimate.linear() = Eigen::Quaterniond(Td.topLeftCorner<3, 3>()).normalized().toRotationMatrix();
  estimate.translation() = Td.topRightCorner<3, 1>();

  const Fitness fit = measure_fitness(*src, estimate.matrix().cast<float>(), *tree, config.fitness_distance);
  result.T_target_source = estimate;
  result.fitness = fit.mean_squared;
  result.inlier_ratio = fit.inlier_ratio;
  result.converged = true;
  return result;
}

}  // namespace tsgraphs::registration
