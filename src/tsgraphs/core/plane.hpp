#pragma once
/// Infinite plane n.x + d = 0 with unit normal n (the S-Graphs (n, d) convention).
#include <Eigen/Geometry>

namespace tsgraphs {

struct Plane {
  Eigen::Vector3d n = Eigen::Vector3d::UnitZ();  ///< unit normal
  double d = 0.0;                                ///< offset: n.x + d = 0 on the plane

  /// Plane through `point` with normal `normal` (normalised here).
  static Plane from_point_normal(const Eigen::Vector3d& point, const Eigen::Vector3d& normal) {
    Plane p;
    p.n = normal.normalized();
    p.d = -p.n.dot(point);
    return p;
  }
  /// Signed distance of x from the plane, positive on the side n points to.
  double signed_distance(const Eigen::Vector3d& x) const { return n.dot(x) + d; }
  /// The same plane expressed in frame A, given T_AB (this plane is in frame B).
  Plane transformed(const Eigen::Isometry3d& T_AB) const {
    Plane p;
    p.n = T_AB.linear() * n;
    p.d = d - p.n.dot(T_AB.translation());
    return p;
  }
  /// The closest point of the plane to the origin.
  Eigen::Vector3d closest_to_origin() const { return -d * n; }
};

}  // namespace tsgraphs
