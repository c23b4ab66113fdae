#pragma once
/// How steeply the ground rises round each traversable node: a floor is level, a ramp is not.
/// A ramp both rises (its nodes' heights) and tilts (their normals); a step only rises (the
/// ground is level on either side of it), and the normals of a sparse sensor's ring of nodes
/// only tilt (each fitted to a line of points, all biased the same way along the ring), so
/// the slope is the lesser of the two.
#include <Eigen/Core>
#include <vector>

namespace tsgraphs::ground {

/// Per node, the rise per metre of the ground round it, over the nodes within `radius` of it
/// along each axis (binned on cells of `cell`, m): the lesser of the height gradient of the
/// plane fitted to their positions (0 when they lie on a line) and the length of the mean of
/// their normals' gradients (-n_xy / n_z). Nodes with a non-finite position or a horizontal or
/// non-finite normal count for nothing. Throws std::invalid_argument unless cell > 0,
/// radius >= 0 (both finite) and the two vectors have one size.
std::vector<double> ground_slopes(const std::vector<Eigen::Vector3d>& positions,
                                  const std::vector<Eigen::Vector3d>& normals, double cell, double radius);

}  // namespace tsgraphs::ground
