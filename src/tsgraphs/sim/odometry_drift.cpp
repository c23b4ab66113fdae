#include "tsgraphs/sim/odometry_drift.hpp"

#include <cmath>
#include <random>

namespace tsgraphs::sim {

std::vector<Pose3> drift_odometry(const std::vector<Pose3>& truth, const scene::OdometryNoise& noise,
                                  std::uint64_t seed) {
  std::vector<Pose3> odom;
  if (truth.empty()) return odom;
  // A stream of its own, so that range noise and drift do not share random numbers.
  std::mt19937_64 rng(seed ^ 0x6f646f6d65747279ULL);
  std::normal_distribution<double> gauss(0.0, 1.0);
  odom.reserve(truth.size());
  odom.push_back(truth.front());
  for (std::size_t k = 1; k < truth.size(); ++k) {
    const Pose3 delta = truth[k - 1].inverse() * truth[k];
    const double d = delta.translation().norm();
    const double a = std::abs(yaw_of(delta));
    const double trans_std = noise.trans_noise_per_m * std::sqrt(d);
    const double yaw_std = std::sqrt(noise.yaw_noise_per_rad * noise.yaw_noise_per_rad * a +
                                     noise.yaw_noise_per_m * noise.yaw_noise_per_m * d);
    // Draw all four numbers every step, so a zero std changes no later draw.
    // One draw per statement: the order of a call's arguments is unspecified (gcc and clang
    // differ); z, y, x is the order gcc took, kept so that sequences stay as they were.
    const double dz = gauss(rng);
    const double dy = gauss(rng);
    const double dx = gauss(rng);
    const Eigen::Vector3d dt(dx, dy, dz);
    const double dyaw = gauss(rng);
    Pose3 noisy = delta;
    noisy.translation() += trans_std * dt;
    noisy.linear() =
        Eigen::AngleAxisd(yaw_std * dyaw, Eigen::Vector3d::UnitZ()).toRotationMatrix() * delta.linear();
    odom.push_back(odom.back() * noisy);
  }
  return odom;
}

}  // namespace tsgraphs::sim
