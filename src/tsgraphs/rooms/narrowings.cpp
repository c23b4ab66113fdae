#include "tsgraphs/rooms/narrowings.hpp"

#include <algorithm>
#include <stdexcept>

#include "tsgraphs/core/raster_regions.hpp"

namespace tsgraphs::rooms {

namespace {

/// The spaces of the flood: a union-find whose roots keep their widest clearance.
struct Spaces {
  std::vector<int> parent;
  std::vector<float> peak;  ///< the clearance of each space's widest point

  int root(int k) {
    while (parent[at(k)] != k) {
      parent[at(k)] = parent[at(parent[at(k)])];
      k = parent[at(k)];
    }
    return k;
  }
  int add(float clearance) {
    parent.push_back(static_cast<int>(parent.size()));
    peak.push_back(clearance);
    return parent.back();
  }
  void join(int into, int other) {
    parent[at(other)] = into;
    peak[at(into)] = std::max(peak[at(into)], peak[at(other)]);
  }
  static std::size_t at(int k) { return static_cast<std::size_t>(k); }
};

/// The walkable cells and the obstacles they surround that are smaller than `max_island_area`
/// (furniture, pillars, what the sensor could not see behind them): the flood goes round those
/// as over the floor.
std::vector<std::uint8_t> floor_round_islands(const GridFrame& f, const std::vector<std::uint8_t>& walkable,
                                              double max_island_area) {
  std::vector<std::uint8_t> blocked(f.size());
  for (std::size_t i = 0; i < f.size(); ++i) blocked[i] = walkable[i] ? 0 : 1;
  const std::vector<std::uint8_t> islands =
      enclosed_regions(blocked, f.cols, f.rows, max_island_area / (f.resolution * f.resolution));
  std::vector<std::uint8_t> open = walkable;
  for (std::size_t i = 0; i < f.size(); ++i) open[i] = open[i] || islands[i];
  return open;
}

/// Floods the `open` cells from the highest clearance down; returns each cell's space (-1 for
/// none), `spaces` holding which spaces were joined.
std::vector<int> flood(const GridFrame& f, const std::vector<std::uint8_t>& open, double max_half_width,
                       double narrowing, Spaces* spaces) {
  const std::vector<float> clearance = distance_transform(f, open);
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < f.size(); ++i)
    if (open[i]) order.push_back(i);
  // Highest clearance first; the index breaks ties, so the result does not depend on the sort.
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return clearance[a] != clearance[b] ? clearance[a] > clearance[b] : a < b;
  });
  const auto wider = [&](int a, int b) {
    const float pa = spaces->peak[Spaces::at(a)], pb = spaces->peak[Spaces::at(b)];
    return pa != pb ? pa > pb : a < b;
  };
  std::vector<int> space(f.size(), -1);
  static const int kDc[4] = {1, -1, 0, 0};
  static const int kDr[4] = {0, 0, 1, -1};
  for (std::size_t i : order) {
    const int c = static_cast<int>(i % f.cols), r = static_cast<int>(i / f.cols);
    int roots[4];
    int n_roots = 0;
    for (int k = 0; k < 4; ++k) {
      const int cc = c + kDc[k], rr = r + kDr[k];
      if (!f.inside(cc, rr) || space[f.index(cc, rr)] < 0) continue;
      const int root = spaces->root(space[f.index(cc, rr)]);
      if (std::find(roots, roots + n_roots, root) == roots + n_roots) roots[n_roots++] = root;
    }
    if (n_roots == 0) {
      space[i] = spaces->add(clearance[i]);
      continue;
    }
    // The cell belongs to the widest space it touches; the others meet it here, at a saddle.
    for (int k = 1; k < n_roots; ++k)
      for (int j = k; j > 0 && wider(roots[j], roots[j - 1]); --j) std::swap(roots[j], roots[j - 1]);
    space[i] = roots[0];
    for (int k = 1; k < n_roots; ++k) {
      const int a = spaces->root(roots[0]), b = spaces->root(roots[k]);
      if (a == b) continue;
      const double smaller = std::min(spaces->peak[Spaces::at(a)], spaces->peak[Spaces::at(b)]);
      if (clearance[i] > max_half_width || clearance[i] > narrowing * smaller) spaces->join(a, b);
    }
  }
  return space;
}

}  // namespace

int split_at_narrowings(const GridFrame& f, const std::vector<std::uint8_t>& walkable, double max_half_width,
                        double narrowing, double max_island_area, std::vector<int>* label) {
  if (walkable.size() != f.size())
    throw std::invalid_argument("split_at_narrowings: the mask does not match the frame");
  Spaces spaces;
  const std::vector<int> space =
      flood(f, floor_round_islands(f, walkable, max_island_area), max_half_width, narrowing, &spaces);
  label->assign(f.size(), -1);
  std::vector<int> renumber(spaces.parent.size(), -1);
  int n = 0;
  for (std::size_t i = 0; i < f.size(); ++i) {
    if (space[i] < 0 || !walkable[i]) continue;  // an island's cells are no space
    const int root = spaces.root(space[i]);
    if (renumber[Spaces::at(root)] < 0) renumber[Spaces::at(root)] = n++;
    (*label)[i] = renumber[Spaces::at(root)];
  }
  return n;
}

}  // namespace tsgraphs::rooms
