#include "tsgraphs/freespace/planar_index.hpp"

#include <nanoflann.hpp>

#include <algorithm>
#include <cstdint>
#include <utility>

namespace tsgraphs::freespace {
namespace {

// nanoflann's leaf size: the walls module measured 6 to 24 the same.
constexpr std::size_t kKdTreeLeafSize = 16;

struct XyAdaptor {
  const std::vector<Eigen::Vector2d>& pts;
  std::size_t kdtree_get_point_count() const { return pts.size(); }
  double kdtree_get_pt(std::size_t i, std::size_t dim) const { return pts[i][static_cast<int>(dim)]; }
  template <class BBox>
  bool kdtree_get_bbox(BBox&) const {
    return false;
  }
};
using KdTree =
    nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, XyAdaptor>, XyAdaptor, 2, std::uint32_t>;

}  // namespace

struct PlanarIndex::Impl {
  std::vector<Eigen::Vector2d> xy;
  XyAdaptor adaptor{xy};
  // Built by its constructor, after xy and adaptor (member order).
  KdTree tree{2, adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(kKdTreeLeafSize)};

  explicit Impl(std::vector<Eigen::Vector2d> points) : xy(std::move(points)) {}
};

PlanarIndex::PlanarIndex(const std::vector<Eigen::Vector3d>& points) {
  std::vector<Eigen::Vector2d> xy;
  xy.reserve(points.size());
  for (const auto& p : points) xy.push_back(p.head<2>());
  impl_ = std::make_unique<Impl>(std::move(xy));
}

PlanarIndex::~PlanarIndex() = default;

void PlanarIndex::within(const Eigen::Vector3d& p, double radius, std::vector<int>& out) const {
  out.clear();
  if (impl_->xy.empty() || !(radius > 0.0)) return;
  const double query[2] = {p.x(), p.y()};
  // nanoflann's L2 radius is squared and the bound strict.
  std::vector<std::pair<std::uint32_t, double>> matches;
  impl_->tree.radiusSearch(query, radius * radius, matches, nanoflann::SearchParams(0, 0.0f, false));
  out.reserve(matches.size());
  for (const auto& m : matches) out.push_back(static_cast<int>(m.first));
  std::sort(out.begin(), out.end());
}

}  // namespace tsgraphs::freespace
