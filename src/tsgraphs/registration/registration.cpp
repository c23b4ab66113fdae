// GCC 12 reports false -Warray-bounds in Eigen's SSE loads of Vector3f, inlined from PCL's
// ICP base (Umeyama); the code is Eigen's and PCL's, not ours. Set before any Eigen header.
#pragma GCC diagnostic ignored "-Warray-bounds"
#include "tsgraphs/registration/registration.hpp"

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/registration/gicp.h>
#include <pcl/search/kdtree.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "tsgraphs/core/kd_tree.hpp"
#include "tsgraphs/core/voxel_grid.hpp"

namespace tsgraphs::registration {
namespace {

using PclPoint = pcl::PointXYZ;
using PclCloud = pcl::PointCloud<PclPoint>;

// GICP's covariance of a point: its neighbourhood's principal directions, with the two largest
// spreads set to 1 and the smallest to this (the surface's thickness relative to its extent):
// PCL's default, which the registration used before covariances were prepared here.
constexpr double kGicpEpsilon = 0.001;

/// PCL's k-d tree interface over the project's nanoflann tree. PCL's own (FLANN) enters an
/// OpenMP parallel region for every single-point query, which cost more than the search itself
/// in GICP's per-point correspondence loop.
class NanoflannSearch : public pcl::search::KdTree<PclPoint> {
 public:
  explicit NanoflannSearch(const PclCloud::ConstPtr& cloud) : pcl::search::KdTree<PclPoint>(true) {
    input_ = cloud;
    points_.reserve(cloud->size());
    for (const PclPoint& p : cloud->points) points_.emplace_back(p.x, p.y, p.z);
    tree_ = std::make_unique<KdTree3f>(points_);
  }

  // GICP is given this tree with "no recompute"; a new cloud would be a misuse.
  void setInputCloud(const PclCloud::ConstPtr& cloud, const pcl::IndicesConstPtr& indices) override {
    if (cloud != input_ || indices)
      throw std::logic_error("NanoflannSearch: the cloud is fixed at construction");
  }

  int nearestKSearch(const PclPoint& point, int k, pcl::Indices& k_indices,
                     std::vector<float>& k_sqr_distances) const override {
    if (k <= 0) return 0;
    const std::size_t kk = static_cast<std::size_t>(k);
    // nanoflann's index type is unsigned, PCL's signed: one buffer per thread between them,
    // so that a prepared cloud can be searched from several threads.
    thread_local std::vector<std::uint32_t> scratch;
    scratch.resize(kk);
    k_sqr_distances.resize(kk);
    const std::size_t found = tree_->knn(point.data, kk, scratch.data(), k_sqr_distances.data());
    k_indices.assign(scratch.begin(), scratch.begin() + static_cast<std::ptrdiff_t>(found));
    k_sqr_distances.resize(found);
    return static_cast<int>(found);
  }

  int radiusSearch(const PclPoint&, double, pcl::Indices&, std::vector<float>&, unsigned int) const override {
    throw std::logic_error("NanoflannSearch: radius search is not used by GICP");
  }

  const std::vector<Eigen::Vector3f>& points() const { return points_; }
  const KdTree3f& tree() const { return *tree_; }

 private:
  std::vector<Eigen::Vector3f> points_;
  std::unique_ptr<KdTree3f> tree_;
};

using Covariances = pcl::GeneralizedIterativeClosestPoint<PclPoint, PclPoint>::MatricesVector;

/// GICP's covariance of every point over its k nearest neighbours (itself included), as PCL
/// computes it: PCA of the neighbourhood, spreads replaced by 1, 1, kGicpEpsilon.
std::shared_ptr<Covariances> point_covariances(const NanoflannSearch& search, int k) {
  const std::vector<Eigen::Vector3f>& pts = search.points();
  auto out = std::make_shared<Covariances>(pts.size());
  const std::size_t kk = static_cast<std::size_t>(k);
  std::vector<std::uint32_t> nb(kk);
  std::vector<float> d2(kk);
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const std::size_t found = search.tree().knn(pts[i].data(), kk, nb.data(), d2.data());
    // Moments relative to the query point: no cancellation far from the origin.
    Eigen::Vector3d s = Eigen::Vector3d::Zero();
    Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
    for (std::size_t j = 0; j < found; ++j) {
      const Eigen::Vector3d q = (pts[nb[j]] - pts[i]).cast<double>();
      s += q;
      m.noalias() += q * q.transpose();
    }
    const double inv = 1.0 / static_cast<double>(std::max<std::size_t>(found, 1));
    const Eigen::Matrix3d cov = m * inv - (s * inv) * (s * inv).transpose();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es;
    es.computeDirect(cov);
    // Eigenvalues ascending: the first eigenvector is the surface's normal.
    const Eigen::Matrix3d U = es.eigenvectors();
    Eigen::Matrix3d& c = (*out)[i];
    c = U.col(1) * U.col(1).transpose() + U.col(2) * U.col(2).transpose() +
        kGicpEpsilon * U.col(0) * U.col(0).transpose();
    if (!c.allFinite()) c = Eigen::Matrix3d::Identity();
  }
  return out;
}

struct Fitness {
  double mean_squared = 0.0;
  double inlier_ratio = 0.0;
  double weakest_direction_share = 0.0;
};

/// Nearest target point of every transformed source point: mean squared distance over the
/// pairs closer than `max_distance`, and their share. No inlier gives the worst mean an
/// inlier could have, max_distance^2.
Fitness measure_fitness(const std::vector<Eigen::Vector3f>& source, const Covariances& source_cov,
                        const Eigen::Matrix4f& T, const KdTree3f& target, const Covariances& target_cov,
                        double max_distance) {
  const double max_sq = max_distance * max_distance;
  const Eigen::Matrix3f R = T.topLeftCorner<3, 3>();
  const Eigen::Vector3f t = T.topRightCorner<3, 1>();
  std::uint32_t index = 0;
  float dist_sq = 0.0f;
  double sum = 0.0;
  std::size_t inliers = 0;
  const Eigen::Matrix3d Rd = R.cast<double>();
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < source.size(); ++i) {
    const Eigen::Vector3f q = R * source[i] + t;
    if (target.knn(q.data(), 1, &index, &dist_sq) < 1) continue;
    if (dist_sq <= max_sq) {
      sum += dist_sq;
      ++inliers;
      H += (Rd * source_cov[i] * Rd.transpose() + target_cov[index]).inverse();
    }
  }
  Fitness f;
  f.mean_squared = inliers > 0 ? sum / static_cast<double>(inliers) : max_sq;
  f.inlier_ratio = source.empty() ? 0.0 : static_cast<double>(inliers) / static_cast<double>(source.size());
  if (inliers > 0) {
    // A pair pins a direction along its surfaces' normal with 1 / (2 eps) and across it with
    // 1 / 2 (GICP's spreads 1, 1, eps): the weakest direction's information per pair says
    // which share of the pairs face it.
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es;
    es.computeDirect(H / static_cast<double>(inliers), Eigen::EigenvaluesOnly);
    const double across = 0.5, facing = 0.5 / kGicpEpsilon;
    f.weakest_direction_share = std::clamp((es.eigenvalues()(0) - across) / (facing - across), 0.0, 1.0);
  }
  return f;
}

}  // namespace

struct PreparedCloud::Data {
  double voxel_size = 0.0;
  int k = 0;
  PclCloud::Ptr cloud;
  std::shared_ptr<const NanoflannSearch> search;   // null when the cloud has fewer than k points
  std::shared_ptr<const Covariances> covariances;  // GICP's, shared with every registration
};

PreparedCloud::PreparedCloud() = default;
PreparedCloud::~PreparedCloud() = default;
PreparedCloud::PreparedCloud(const PreparedCloud&) = default;
PreparedCloud& PreparedCloud::operator=(const PreparedCloud&) = default;

std::size_t PreparedCloud::size() const { return data_ ? data_->cloud->size() : 0; }

PreparedCloud prepare_cloud(const PointCloud& cloud, const RegistrationConfig& config) {
  check_config(config, "RegistrationConfig");
  auto data = std::make_shared<PreparedCloud::Data>();
  data->voxel_size = config.voxel_size;
  data->k = config.k_correspondences;
  data->cloud = pcl::make_shared<PclCloud>();
  for (const Eigen::Vector3f& p : voxel_downsample(cloud, config.voxel_size).points)
    data->cloud->push_back(PclPoint(p.x(), p.y(), p.z()));
  // GICP's covariances read k neighbours of every point: smaller clouds cannot be matched.
  if (data->cloud->size() >= static_cast<std::size_t>(config.k_correspondences)) {
    data->search = std::make_shared<NanoflannSearch>(data->cloud);
    data->covariances = point_covariances(*data->search, config.k_correspondences);
  }
  PreparedCloud out;
  out.data_ = std::move(data);
  return out;
}

RegistrationResult register_clouds(const PreparedCloud& source, const PreparedCloud& target,
                                   const Pose3& initial_guess, const RegistrationConfig& config) {
  check_config(config, "RegistrationConfig");
  for (const PreparedCloud* c : {&source, &target}) {
    if (!c->data_) throw std::invalid_argument("register_clouds: a cloud was not prepared");
    if (c->data_->voxel_size != config.voxel_size || c->data_->k != config.k_correspondences)
      throw std::invalid_argument(
          "register_clouds: a cloud was prepared with another voxel_size or k_correspondences");
  }
  RegistrationResult result;
  result.T_target_source = initial_guess;
  result.fitness = config.fitness_distance * config.fitness_distance;
  if (!initial_guess.matrix().allFinite()) return result;
  const PreparedCloud::Data& src = *source.data_;
  const PreparedCloud::Data& tgt = *target.data_;
  if (!src.search || !tgt.search) return result;

  // The prepared trees, shared: GICP only searches them ("no recompute").
  const auto source_search = std::const_pointer_cast<NanoflannSearch>(src.search);
  const auto target_search = std::const_pointer_cast<NanoflannSearch>(tgt.search);

  pcl::GeneralizedIterativeClosestPoint<PclPoint, PclPoint> gicp;
  gicp.setMaxCorrespondenceDistance(config.max_correspondence_distance);
  gicp.setMaximumIterations(config.max_iterations);
  gicp.setCorrespondenceRandomness(config.k_correspondences);
  // The same bound on every element of the transform's change, rotation and translation.
  gicp.setTransformationEpsilon(config.transformation_epsilon);
  gicp.setRotationEpsilon(config.transformation_epsilon);
  gicp.setInputSource(src.cloud);
  gicp.setInputTarget(tgt.cloud);
  gicp.setSearchMethodSource(source_search, true);
  gicp.setSearchMethodTarget(target_search, true);
  // Set after the clouds (setting a cloud drops its covariances).
  gicp.setSourceCovariances(std::const_pointer_cast<Covariances>(src.covariances));
  gicp.setTargetCovariances(std::const_pointer_cast<Covariances>(tgt.covariances));

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

  const Fitness fit =
      measure_fitness(source_search->points(), *src.covariances, estimate.matrix().cast<float>(),
                      target_search->tree(), *tgt.covariances, config.fitness_distance);
  result.T_target_source = estimate;
  result.fitness = fit.mean_squared;
  result.inlier_ratio = fit.inlier_ratio;
  result.weakest_direction_share = fit.weakest_direction_share;
  result.converged = true;
  return result;
}

RegistrationResult register_clouds(const PointCloud& source, const PointCloud& target,
                                   const Pose3& initial_guess, const RegistrationConfig& config) {
  return register_clouds(prepare_cloud(source, config), prepare_cloud(target, config), initial_guess, config);
}

}  // namespace tsgraphs::registration
