#pragma once
/// Pairwise scan registration (generalised ICP, PCL), used by loop closure to measure the
/// relative pose of two keyframes and to check that the match is good.
#include <cstddef>
#include <memory>

#include "tsgraphs/core/point_cloud.hpp"
#include "tsgraphs/core/pose.hpp"
#include "tsgraphs/core/config_fields.hpp"

namespace tsgraphs::registration {

struct RegistrationConfig {
  double voxel_size = 0.2;
  double max_correspondence_distance = 1.0;
  double fine_correspondence_distance = 0.5;  ///< gate of a second GICP pass from the first one's result (m),
                                              ///< so that far pairs do not bias the final pose; 0 = one pass
  int max_iterations = 64;
  int k_correspondences = 20;
  double transformation_epsilon = 1e-4;
  double fitness_distance = 0.3;

  template <class V>
  void visit(V& v) {
    v("voxel_size", voxel_size, between(0.0, 100.0), "m; both clouds are thinned to this; 0 = keep all");
    v("max_correspondence_distance", max_correspondence_distance, above(0.0, 100.0),
      "m; correspondence gate of the first pass");
    v("fine_correspondence_distance", fine_correspondence_distance, between(0.0, 100.0),
      "m; gate of the second pass, for precision");
    v("max_iterations", max_iterations, between(1, 1000), "GICP iterations");
    v("k_correspondences", k_correspondences, between(3, 100), "neighbours for each point's covariance");
    v("transformation_epsilon", transformation_epsilon, above(0.0, 1.0),
      "convergence: change of the transform between iterations");
    v("fitness_distance", fitness_distance, above(0.0, 100.0),
      "m; only matches nearer than this count in the fitness");
  }
};

struct RegistrationResult {
  Pose3 T_target_source = Pose3::Identity();  ///< maps source points into the target frame
  double fitness = 0.0;  ///< mean squared distance (m^2) of source points to their nearest target point, over
                         ///< those within fitness_distance
  double inlier_ratio =
      0.0;  ///< share of source points within fitness_distance of the target after alignment
  /// How well the matched surfaces pin the translation: the share of the pairs within
  /// fitness_distance whose surfaces face the direction they pin least (from GICP's
  /// translation information, sum of (C_target + R C_source R^T)^-1 over the pairs). Near 0:
  /// nothing faces it (a corridor's length), and the match may have slid along it.
  double weakest_direction_share = 0.0;
  bool converged = false;
};

/// A cloud made ready for registration once, for any number of registrations against others:
/// thinned to voxel_size, indexed, each point's covariance (GICP's plane-like one) computed.
/// Loop closure registers a keyframe against several candidates, and a candidate against
/// several later keyframes: preparing each once is most of a registration's cost saved.
/// Cheap to copy (shared, immutable).
class PreparedCloud {
 public:
  PreparedCloud();
  ~PreparedCloud();
  PreparedCloud(const PreparedCloud&);
  PreparedCloud& operator=(const PreparedCloud&);

  /// Points after thinning (0: nothing to register).
  std::size_t size() const;

  struct Data;  ///< PCL's types, private to registration.cpp

 private:
  friend PreparedCloud prepare_cloud(const PointCloud&, const RegistrationConfig&);
  friend RegistrationResult register_clouds(const PreparedCloud&, const PreparedCloud&, const Pose3&,
                                            const RegistrationConfig&);
  std::shared_ptr<const Data> data_;
};

/// `cloud` thinned to config.voxel_size (non-finite points dropped), indexed, with its points'
/// covariances over config.k_correspondences neighbours. A config out of range is a
/// std::invalid_argument.
PreparedCloud prepare_cloud(const PointCloud& cloud, const RegistrationConfig& config);

/// Aligns `source` to `target` starting from `initial_guess` (T_target_source). Both must be
/// prepared with this config's voxel_size and k_correspondences (else std::invalid_argument).
/// Clouds with fewer than k_correspondences points after thinning, or a non-finite guess, give
/// converged = false (T = the guess, inlier_ratio 0), never an exception; a config out of range
/// (negative sizes, k < 3) is a std::invalid_argument. `converged` is PCL's: the iterations
/// stopped (by epsilon or by max_iterations) without a numerical failure.
RegistrationResult register_clouds(const PreparedCloud& source, const PreparedCloud& target,
                                   const Pose3& initial_guess, const RegistrationConfig& config);

/// The same for clouds not prepared yet (prepares both).
RegistrationResult register_clouds(const PointCloud& source, const PointCloud& target,
                                   const Pose3& initial_guess, const RegistrationConfig& config);

}  // namespace tsgraphs::registration
