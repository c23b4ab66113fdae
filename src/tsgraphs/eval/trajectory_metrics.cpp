#include "tsgraphs/eval/trajectory_metrics.hpp"

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

}  // namespace tsgraphs::eval
