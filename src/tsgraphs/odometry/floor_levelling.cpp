#include "tsgraphs/odometry/floor_levelling.hpp"

#include <pcl/ModelCoefficients.h>
#include <pcl/point_types.h>
#include <pcl/segmentation/sac_segmentation.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace tsgraphs::odometry {
namespace {
constexpr int kRefitRounds = 5;  // least-squares refits at most (they settle in two or three)
}  // namespace

namespace {

using Cloud = pcl::PointCloud<pcl::PointXYZ>;

/// A plane: unit normal towards the sensor (the origin), a point on it, and how many points of
/// the cloud it was fitted to lie within the distance threshold.
struct PlaneFit {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  std::size_t num_inliers = 0;
};

Eigen::Vector3d at(const Cloud& cloud, int i) { return cloud[i].getVector3fMap().cast<double>(); }

/// The plane of `cloud` within max_tilt of z with the most points within the threshold (PCL's
/// RANSAC), at least `min_inliers` of them.
std::optional<PlaneFit> ransac_plane(const Cloud::Ptr& cloud, const FloorLevellingConfig& config,
                                     std::size_t min_inliers) {
  if (cloud->size() < min_inliers) return std::nullopt;
  pcl::SACSegmentation<pcl::PointXYZ> ransac(false);       // false: the fixed seed
  ransac.setModelType(pcl::SACMODEL_PERPENDICULAR_PLANE);  // PCL's name for "normal along the axis"
  // RANSAC, not MSAC: PCL's MSAC stops with an error at the first sample outside the axis
  // constraint.
  ransac.setMethodType(pcl::SAC_RANSAC);
  ransac.setProbability(config.ransac_probability);
  ransac.setAxis(Eigen::Vector3f::UnitZ());
  ransac.setEpsAngle(config.max_tilt_deg * M_PI / 180.0);
  ransac.setDistanceThreshold(config.distance_threshold);
  ransac.setMaxIterations(config.max_iterations);
  ransac.setOptimizeCoefficients(false);  // refitted in double
  ransac.setInputCloud(cloud);
  pcl::PointIndices inliers;
  pcl::ModelCoefficients coefficients;
  ransac.segment(inliers, coefficients);
  if (inliers.indices.size() < min_inliers || coefficients.values.size() < 4) return std::nullopt;
  PlaneFit fit;
  const Eigen::Vector3d n(coefficients.values[0], coefficients.values[1], coefficients.values[2]);
  fit.normal = n.normalized();
  fit.mean = -coefficients.values[3] / n.squaredNorm() * n;  // the plane's point nearest the sensor
  fit.num_inliers = inliers.indices.size();
  return fit;
}

/// Least squares over the points of `cloud` within the threshold of `plane` (the normal is the
/// direction of least spread), then over the points within the threshold of that plane, until
/// they settle.
PlaneFit refine(const Cloud& cloud, PlaneFit plane, const FloorLevellingConfig& config) {
  std::vector<int> members;
  for (int round = 0; round < kRefitRounds; ++round) {
    std::vector<int> next;
    for (int i = 0; i < static_cast<int>(cloud.size()); ++i)
      if (std::abs(plane.normal.dot(at(cloud, i) - plane.mean)) <= config.distance_threshold)
        next.push_back(i);
    if (next.size() < 3 || next == members) break;
    members = std::move(next);
    plane.mean.setZero();
    for (const int i : members) plane.mean += at(cloud, i);
    plane.mean /= static_cast<double>(members.size());
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (const int i : members) {
      const Eigen::Vector3d d = at(cloud, i) - plane.mean;
      cov.noalias() += d * d.transpose();
    }
    plane.normal = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(cov).eigenvectors().col(0).normalized();
  }
  if (plane.normal.dot(-plane.mean) < 0.0) plane.normal = -plane.normal;
  plane.num_inliers = members.size();
  return plane;
}

/// The lowest point of each cell of a grid in the frame level with `plane` (TRAVEL's
/// lowest-point representatives): the floor, where it is seen, and no ring trace above it.
Cloud::Ptr lowest_per_cell(const Cloud& cloud, const PlaneFit& plane, double cell) {
  const Eigen::Matrix3f R = Eigen::Quaterniond::FromTwoVectors(plane.normal, Eigen::Vector3d::UnitZ())
                                .toRotationMatrix()
                                .cast<float>();
  std::map<std::pair<long, long>, std::pair<float, int>> lowest;  // ordered: the same output every time
  for (int i = 0; i < static_cast<int>(cloud.size()); ++i) {
    const Eigen::Vector3f q = R * cloud[i].getVector3fMap();
    const std::pair<long, long> key(std::lround(std::floor(q.x() / cell)),
                                    std::lround(std::floor(q.y() / cell)));
    const auto it = lowest.find(key);
    if (it == lowest.end() || q.z() < it->second.first) lowest[key] = {q.z(), i};
  }
  Cloud::Ptr out(new Cloud);
  for (const auto& [key, value] : lowest) out->push_back(cloud[value.second]);
  return out;
}

}  // namespace

FloorLevel level_from_floor(const PointCloud& scan, const FloorLevellingConfig& config) {
  check_config(config, "FloorLevellingConfig");
  FloorLevel level;
  // Candidates: returns below the sensor, within the range band.
  Cloud::Ptr candidates(new Cloud);
  const double min_sq = config.min_range * config.min_range, max_sq = config.max_range * config.max_range;
  for (const Eigen::Vector3f& p : scan.points) {
    if (!p.allFinite() || p.z() > -config.min_depth) continue;
    const double r_sq = p.squaredNorm();
    if (r_sq >= min_sq && r_sq <= max_sq) candidates->push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
  }
  // A first plane, then the plane of the lowest points in its level frame: the largest plane of
  // a sparse scanner's returns can mix floor rings with ring traces on nearby walls, a few
  // degrees off; the lowest points are the floor's.
  const std::size_t min_inliers = static_cast<std::size_t>(config.min_inliers);
  const std::optional<PlaneFit> first = ransac_plane(candidates, config, min_inliers);
  if (!first) return level;
  const Cloud::Ptr lowest =
      lowest_per_cell(*candidates, refine(*candidates, *first, config), config.cell_size);
  const std::optional<PlaneFit> seed =
      ransac_plane(lowest, config, static_cast<std::size_t>(config.min_cells));
  if (!seed) return level;
  const PlaneFit floor = refine(*candidates, *seed, config);
  // A floor holds more returns than lie below it (a storey below seen through a void,
  // multipath): a sensor tilted beyond max_tilt_deg finds only planes that cut the floor and a
  // wall, with most of the floor beneath them.
  std::size_t below = 0;
  for (const pcl::PointXYZ& p : *candidates)
    if (floor.normal.dot(p.getVector3fMap().cast<double>() - floor.mean) < -config.below_margin) ++below;
  if (floor.num_inliers < min_inliers || below > floor.num_inliers ||
      floor.normal.z() < std::cos(config.max_tilt_deg * M_PI / 180.0))
    return level;

  level.found = true;
  level.height = floor.normal.dot(-floor.mean);
  level.tilt_deg = std::acos(std::min(1.0, floor.normal.z())) * 180.0 / M_PI;
  level.num_inliers = floor.num_inliers;
  // The shortest rotation that takes the floor's normal to z turns nothing about it.
  level.sensor_pose.linear() =
      Eigen::Quaterniond::FromTwoVectors(floor.normal, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  level.sensor_pose.translation() = Eigen::Vector3d(0.0, 0.0, level.height);
  return level;
}

}  // namespace tsgraphs::odometry
