#include "tsgraphs/sim/people.hpp"

#include <algorithm>
#include <cmath>

namespace tsgraphs::sim {

People::People(const scene::Scene& scene) {
  for (const scene::Person& p : scene.people) {
    Walker w;
    w.path = p.path;
    w.along.push_back(0.0);
    for (std::size_t i = 1; i < p.path.size(); ++i)
      w.along.push_back(w.along.back() + (p.path[i] - p.path[i - 1]).norm());
    w.speed = p.speed;
    w.offset = p.offset;
    w.floor = scene.levels.at(p.level).elevation;
    w.height = p.height;
    w.radius = p.radius;
    walkers_.push_back(std::move(w));
  }
}

Eigen::Vector3d People::position(std::size_t i, double t) const {
  const Walker& w = walkers_.at(i);
  const double length = w.along.back();
  // There and back: a saw tooth of period twice the path's length, folded at its end.
  double s = std::fmod(w.offset + w.speed * t, 2.0 * length);
  if (s < 0.0) s += 2.0 * length;
  if (s > length) s = 2.0 * length - s;
  const std::size_t k = std::min<std::size_t>(
      std::upper_bound(w.along.begin(), w.along.end(), s) - w.along.begin(), w.along.size() - 1);
  const double a = w.along[k - 1], b = w.along[k];
  const Eigen::Vector2d xy = w.path[k - 1] + (b > a ? (s - a) / (b - a) : 0.0) * (w.path[k] - w.path[k - 1]);
  return Eigen::Vector3d(xy.x(), xy.y(), w.floor);
}

bool People::occlude(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir, double t, float min_range,
                     float max_range, RayHit* hit) const {
  double nearest = hit->range >= 0.0f ? hit->range : max_range;
  bool found = false;
  for (std::size_t i = 0; i < walkers_.size(); ++i) {
    const Walker& w = walkers_[i];
    const Eigen::Vector3d foot = position(i, t);
    const double top = foot.z() + w.height;
    // The side: |o + s d - c| = r in the plane, within the person's height.
    const Eigen::Vector2d o = origin.head<2>() - foot.head<2>();
    const Eigen::Vector2d d = dir.head<2>();
    const double a = d.squaredNorm();
    const double b = o.dot(d);
    const double c = o.squaredNorm() - w.radius * w.radius;
    if (a > 1e-12 && b * b - a * c >= 0.0) {
      const double s = (-b - std::sqrt(b * b - a * c)) / a;  // entering (from outside)
      const double z = origin.z() + s * dir.z();
      if (s >= min_range && s < nearest && z >= foot.z() && z <= top) {
        const Eigen::Vector2d normal = (o + s * d).normalized();
        nearest = s;
        hit->cos_incidence = static_cast<float>(std::abs(normal.dot(d)));
        found = true;
      }
    }
    // The head: the top disc, from above.
    if (dir.z() < 0.0 && origin.z() > top) {
      const double s = (top - origin.z()) / dir.z();
      if (s >= min_range && s < nearest && (o + s * d).squaredNorm() <= w.radius * w.radius) {
        nearest = s;
        hit->cos_incidence = static_cast<float>(std::abs(dir.z()));
        found = true;
      }
    }
  }
  if (found) {
    hit->range = static_cast<float>(nearest);
    hit->label = static_cast<std::uint32_t>(PointLabel::kPerson);
  }
  return found;
}

}  // namespace tsgraphs::sim
