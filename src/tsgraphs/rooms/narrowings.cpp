#include "tsgraphs/rooms/narrowings.hpp"

#include <algorithm>
#include <stdexcept>

#include "tsgraphs/core/raster_regions.hpp"

namespace tsgraphs::rooms {

namespace {

struct Spaces {
  std::vector<int> parent;
  std::vector<float> peak;  // the clearance of each space's widest point

  int root(int k) {
    while (parent[static_cast<std::size_t>(k)] != k) {
      parent[static_cast<std::size_t>(k)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(k)])];
      k = parent[static_cast<std::size_t>(k)];
    }
    return k;
  }
  int add(float clearance) {
    parent.push_back(static_cast<int>(parent.size()));
    peak.push_back(clearance);
    return parent.back();
  }
  void join(int into, int other) {
    parent[static_cast<std::size_t>(other)] = into;
    peak[static_cast<std::size_t>(into)] = std::max(peak[static_cast<std::size_t>(into)], peak[static_cast<std::size_t>(other)]);
  }
};

}  // namespace

int split_at_narrowings(const GridFrame& f, const std::vector<std::uint8_t>& walkable, double max_half_width,
                        double narrowing, double max_island_area, std::vector<int>* label) {
  if (walkable.size() != f.size()) throw std::invalid_argument("split_at_narrowings: the mask does not match the frame");
  // Obstacles the walkable area surrounds (furniture, pillars, what the sensor could not see
  // behind them) bound no space: the flood goes round them as over the floor.
  std::vector<std::uint8_t> blocked(f.size());
  for (std::size_t i = 0; i < f.size(); ++i) blocked[i] = walkable[i] ? 0 : 1;
  const std::vector<std::uint8_t> islands =
      enclosed_regions(blocked, f.cols, f.rows, max_island_area / (f.resolution * f.resolution));
  std::vector<std::uint8_t> open = walkable;
  for (std::size_t i = 0; i < f.size(); ++i) open[i] = open[i] || islands[i];
  const std::vector<float> clearance = distance_transform(f, open);
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < f.size(); ++i)
    if (open[i]) order.push_back(i);
  // Highest clearance first; the index breaks ties, so the result does not depend on the sort.
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return clearance[a] != clearance[b] ? clearance[a] > clearance[b] : a < b;
  });
  std::vector<int> space(f.size(), -1);
  Spaces spaces;
  static const int kDc[4] = {1, -1, 0, 0};
  static const int kDr[4] = {0, 0, 1, -1};
  for (std::size_t i : order) {
    const int c = static_cast<int>(i % f.cols), r = static_cast<int>(i / f.cols);
    int roots[4];
    int n_roots = 0;
    for (int k = 0; k < 4; ++k) {
      const int cc = c + kDc[k], rr = r + kDr[k];
      if (!f.inside(cc, rr)) continue;
      const int s = space[f.index(cc, rr)];
      if (s < 0) continue;
      const int root = spaces.root(s);
      if (std::find(roots, roots + n_roots, root) == roots + n_roots) roots[n_roots++] = root;
    }
    if (n_roots == 0) {
      space[i] = spaces.add(clearance[i]);
      continue;
    }
    // The cell belongs to the widest space it touches; the others meet it here, at a saddle.
    const auto wider = [&](int a, int b) {
      const float pa = spaces.peak[static_cast<std::size_t>(a)], pb = spaces.peak[static_cast<std::size_t>(b)];
      return pa != pb ? pa > pb : a < b;
    };
    for (int k = 1; k < n_roots; ++k)
      for (int j = k; j > 0 && wider(roots[j], roots[j - 1]); --j) std::swap(roots[j], roots[j - 1]);
    space[i] = roots[0];
    const double saddle = clearance[i];
    for (int k = 1; k < n_roots; ++k) {
      const int a = spaces.root(roots[0]), b = spaces.root(roots[k]);
      if (a == b) continue;
      const double smaller = std::min(spaces.peak[static_cast<std::size_t>(a)], spaces.peak[static_cast<std::size_t>(b)]);
      if (saddle > max_half_width || saddle > narrowing * smaller) spaces.join(a, b);
    }
  }
  label->assign(f.size(), -1);
  std::vector<int> renumber(spaces.parent.size(), -1);
  int n = 0;
  for (std::size_t i = 0; i < f.size(); ++i) {
    if (space[i] < 0 || !walkable[i]) continue;
    const int root = spaces.root(space[i]);
    if (renumber[static_cast<std::size_t>(root)] < 0) renumber[static_cast<std::size_t>(root)] = n++;
    (*label)[i] = renumber[static_cast<std::size_t>(root)];
  }
  return n;
}

}  // namespace tsgraphs::rooms
