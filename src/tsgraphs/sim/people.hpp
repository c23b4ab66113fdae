#pragma once
/// People walking through the scans (scene `people:`): vertical cylinders on their level's
/// floor, each walking its path to the end and back. They are not in the ray caster's static
/// mesh; a ray that meets one before the mesh returns from the person instead.
#include <Eigen/Core>
#include <vector>

#include "tsgraphs/scene/scene.hpp"
#include "tsgraphs/sim/ray_caster.hpp"

namespace tsgraphs::sim {

class People {
 public:
  explicit People(const scene::Scene& scene);

  bool empty() const { return walkers_.empty(); }
  std::size_t size() const { return walkers_.size(); }
  /// Where person i stands at time t (s): (x, y) on the path, z its level's floor.
  Eigen::Vector3d position(std::size_t i, double t) const;
  /// The nearest person the ray from `origin` along unit `dir` meets at time t between
  /// min_range and the hit it has (or max_range when it has none): the hit becomes that
  /// person's (label kPerson). Returns whether it did.
  bool occlude(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir, double t, float min_range,
               float max_range, RayHit* hit) const;

 private:
  struct Walker {
    std::vector<Eigen::Vector2d> path;
    std::vector<double> along;  ///< distance walked to each path point
    double speed = 0.0, offset = 0.0, floor = 0.0, height = 0.0, radius = 0.0;
  };
  std::vector<Walker> walkers_;
};

}  // namespace tsgraphs::sim
