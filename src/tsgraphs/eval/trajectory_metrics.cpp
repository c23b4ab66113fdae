#include "tsgraphs/eval/trajectory_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace tsgraphs::eval {

double ate_loop(const std::vector<Pose3>& estimate) {
  if (estimate.size() < 2) return 0.0;
  return (estimate.back().translation() - estimate.front().translation()).norm();
}

double ate_rmse(const std::vector<Pose3>& estimate, const std::vector<Pose3>& truth) {
  if (estimate.size() != truth.size())
    throw std::invalid_argument("ate_rmse: " + std::to_string(estimate.size()) + " estimated poses, " +
                                std::to_string(truth.size()) + " true ones");
  if (estimate.empty()) return 0.0;
  const Pose3 align = truth.front() * estimate.front().inverse();
  double sum = 0.0;
  for (std::size_t i = 0; i < estimate.size(); ++i)
    sum += ((align * estimate[i]).translation() - truth[i].translation()).squaredNorm();
  return std::sqrt(sum / static_cast<double>(estimate.size()));
}

double segment_drift(const std::vector<Pose3>& estimate, const std::vector<Pose3>& truth,
                     const std::vector<double>& lengths, std::size_t stride) {
  if (estimate.size() != truth.size())
    throw std::invalid_argument("segment_drift: " + std::to_string(estimate.size()) + " estimated poses, " +
                                std::to_string(truth.size()) + " true ones");
  if (stride == 0) throw std::invalid_argument("segment_drift: stride must be >= 1");
  std::vector<double> along(truth.size(), 0.0);  // true path length up to each pose
  for (std::size_t i = 1; i < truth.size(); ++i)
    along[i] = along[i - 1] + (truth[i].translation() - truth[i - 1].translation()).norm();
  double sum = 0.0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < truth.size(); i += stride) {
    for (const double length : lengths) {
      const auto end =
          std::lower_bound(along.begin() + static_cast<std::ptrdiff_t>(i), along.end(), along[i] + length);
      if (end == along.end() || !(length > 0.0)) continue;
      const std::size_t j = static_cast<std::size_t>(end - along.begin());
      const Pose3 error = (truth[i].inverse() * truth[j]).inverse() * (estimate[i].inverse() * estimate[j]);
      sum += error.translation().norm() / length;
      ++count;
    }
  }
  return count == 0 ? -1.0 : sum / static_cast<double>(count);
}

}  // namespace tsgraphs::eval
