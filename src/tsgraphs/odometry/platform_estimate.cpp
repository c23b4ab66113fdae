#include "tsgraphs/odometry/platform_estimate.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>

namespace tsgraphs::odometry {
namespace {

double median(std::vector<double> v) {
  const std::size_t mid = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(mid), v.end());
  if (v.size() % 2 == 1) return v[mid];
  const double upper = v[mid];
  return 0.5 * (upper + *std::max_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(mid)));
}

}  // namespace

BeamLayout measure_beam_layout(const PointCloud& scan, const PlatformEstimateConfig& config) {
  check_config(config, "PlatformEstimateConfig");
  constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;
  std::vector<double> elevations;
  elevations.reserve(scan.size());
  const double min_sq = config.ring_min_range * config.ring_min_range;
  for (const Eigen::Vector3f& p : scan.points) {
    if (!p.allFinite() || p.squaredNorm() < min_sq) continue;
    elevations.push_back(std::atan2(static_cast<double>(p.z()), std::hypot(p.x(), p.y())) * kRadToDeg);
  }
  std::sort(elevations.begin(), elevations.end());
  // Rings: runs of elevations with no gap wider than ring_gap_deg; each ring's elevation is
  // its median.
  std::vector<double> rings;
  for (std::size_t begin = 0; begin < elevations.size();) {
    std::size_t end = begin + 1;
    while (end < elevations.size() && elevations[end] - elevations[end - 1] <= config.ring_gap_deg) ++end;
    if (end - begin >= static_cast<std::size_t>(config.ring_min_points))
      rings.push_back(elevations[(begin + end) / 2]);
    begin = end;
  }
  BeamLayout layout;
  layout.rings = static_cast<int>(rings.size());
  if (rings.empty()) return layout;
  layout.lowest_deg = rings.front();
  layout.highest_deg = rings.back();
  if (rings.size() >= 2) {
    std::vector<double> gaps;
    for (std::size_t i = 1; i < rings.size(); ++i) gaps.push_back(rings[i] - rings[i - 1]);
    layout.spacing_deg = median(gaps);
  }
  return layout;
}

namespace {

constexpr int kRefits = 3;               // plane refits of the floor's returns (they settle in one or two)
constexpr double kMinFloorSpread = 0.5;  // m (sd) both ways: floor returns that fix a plane's tilt

/// The lowest return of each grid cell in the frame whose z is `up` (z: height over the sensor).
std::vector<Eigen::Vector3d> lowest_per_cell(const PointCloud& scan, const Eigen::Matrix3d& R_level_sensor,
                                             const FloorLevellingConfig& levelling) {
  std::map<std::pair<long, long>, Eigen::Vector3d> lowest;  // ordered: the same output every time
  const double min_sq = levelling.min_range * levelling.min_range,
               max_sq = levelling.max_range * levelling.max_range;
  for (const Eigen::Vector3f& p : scan.points) {
    if (!p.allFinite()) continue;
    const Eigen::Vector3d q = R_level_sensor * p.cast<double>();
    const double r_sq = q.head<2>().squaredNorm();
    if (q.z() > -levelling.min_depth || r_sq < min_sq || r_sq > max_sq) continue;
    const std::pair<long, long> key(std::lround(std::floor(q.x() / levelling.cell_size)),
                                    std::lround(std::floor(q.y() / levelling.cell_size)));
    const auto it = lowest.find(key);
    if (it == lowest.end() || q.z() < it->second.z()) lowest[key] = q;
  }
  std::vector<Eigen::Vector3d> out;
  out.reserve(lowest.size());
  for (const auto& [key, q] : lowest) out.push_back(q);
  return out;
}

}  // namespace

FloorHeight floor_height(const PointCloud& scan, const Eigen::Vector3d& up, bool fit_tilt,
                         const FloorLevellingConfig& levelling, const PlatformEstimateConfig& config) {
  check_config(config, "PlatformEstimateConfig");
  check_config(levelling, "FloorLevellingConfig");
  FloorHeight out;
  Eigen::Vector3d normal = up.normalized();
  double height = 0.0;
  std::size_t cells = 0;
  for (int round = 0; round <= (fit_tilt ? kRefits : 1); ++round) {
    const Eigen::Matrix3d R =
        Eigen::Quaterniond::FromTwoVectors(normal, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    const std::vector<Eigen::Vector3d> low = lowest_per_cell(scan, R, levelling);
    if (low.empty()) return out;
    // The fullest height bin (the first round) or the returns near the plane found (refits).
    std::vector<Eigen::Vector3d> members;
    if (round == 0) {
      std::map<long, std::size_t> bins;
      for (const Eigen::Vector3d& q : low) ++bins[std::lround(std::floor(q.z() / config.floor_bin))];
      long best = 0;
      std::size_t best_count = 0;
      for (const auto& [bin, count] : bins) {
        // A level's returns straddle two bins: count each bin with its neighbours.
        const auto near = [&bins](long b) {
          const auto it = bins.find(b);
          return it == bins.end() ? std::size_t{0} : it->second;
        };
        const std::size_t c = count + near(bin - 1) + near(bin + 1);
        if (c > best_count) {
          best_count = c;
          best = bin;
        }
      }
      height = -(static_cast<double>(best) + 0.5) * config.floor_bin;
    }
    for (const Eigen::Vector3d& q : low)
      if (std::abs(q.z() + height) <= levelling.distance_threshold) members.push_back(R.transpose() * q);
    cells = members.size();
    if (cells < static_cast<std::size_t>(levelling.min_cells)) return out;
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d& m : members) mean += m;
    mean /= static_cast<double>(cells);
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (const Eigen::Vector3d& m : members) cov.noalias() += (m - mean) * (m - mean).transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov / static_cast<double>(cells));
    Eigen::Vector3d n = eig.eigenvectors().col(0).normalized();
    if (n.dot(normal) < 0.0) n = -n;
    // Floor seen along one strip (an arc of one ring, a corridor) fixes no tilt across it: the
    // plane is refitted only when its returns spread both ways.
    if (fit_tilt && std::sqrt(eig.eigenvalues()(1)) >= kMinFloorSpread) normal = n;
    height = normal.dot(-mean);
  }
  out.found = height > 0.0 && normal.z() >= std::cos(levelling.max_tilt_deg * M_PI / 180.0);
  out.height = height;
  out.tilt_deg = std::acos(std::min(1.0, normal.z())) * 180.0 / M_PI;
  out.num_cells = cells;
  return out;
}

PlatformEstimate estimate_platform(const std::vector<PointCloud>& scans,
                                   const FloorLevellingConfig& levelling,
                                   const PlatformEstimateConfig& config,
                                   const std::vector<Eigen::Vector3d>& ups) {
  check_config(config, "PlatformEstimateConfig");
  if (!ups.empty() && ups.size() != scans.size())
    throw std::invalid_argument("estimate_platform: " + std::to_string(ups.size()) + " up directions for " +
                                std::to_string(scans.size()) + " scans");
  PlatformEstimate estimate;
  std::vector<double> heights, tilts;
  const std::size_t n = std::min(scans.size(), static_cast<std::size_t>(config.scans));
  for (std::size_t i = 0; i < n; ++i) {
    ++estimate.scans_measured;
    std::optional<Eigen::Vector3d> up;
    if (!ups.empty()) {
      up = ups[i];
    } else {
      const FloorLevel level = level_from_floor(scans[i], levelling);
      if (level.found) up = level.sensor_pose.linear().transpose() * Eigen::Vector3d::UnitZ();
    }
    const FloorHeight floor =
        up ? floor_height(scans[i], *up, ups.empty(), levelling, config) : FloorHeight{};
    if (floor.found) {
      heights.push_back(floor.height);
      tilts.push_back(floor.tilt_deg);
    }
    const BeamLayout beams = measure_beam_layout(scans[i], config);
    if (beams.rings > estimate.beams.rings) estimate.beams = beams;
  }
  estimate.floors_found = heights.size();
  if (heights.empty()) return estimate;
  estimate.height_found = true;
  estimate.height = median(heights);
  estimate.height_spread =
      *std::max_element(heights.begin(), heights.end()) - *std::min_element(heights.begin(), heights.end());
  estimate.tilt_deg = median(tilts);
  return estimate;
}

}  // namespace tsgraphs::odometry
