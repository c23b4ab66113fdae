#include "tsgraphs/map_import/map_rooms.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <limits>
#include <stdexcept>

#include "tsgraphs/core/grid_frame.hpp"
#include "tsgraphs/core/raster_regions.hpp"

namespace tsgraphs::map_import {
namespace {

constexpr float kDistanceSlack = 1e-4f;  // distances are square roots of integers: float rounding
constexpr std::array<std::array<int, 2>, 4> kSides = {{{1, 0}, {-1, 0}, {0, 1}, {0, -1}}};

/// A sub-raster [c0, c0 + cols) x [r0, r0 + rows) of the cols_all-wide raster.
struct Window {
  int c0 = 0, r0 = 0, cols = 0, rows = 0, cols_all = 0;

  std::size_t size() const { return static_cast<std::size_t>(cols) * rows; }
  bool inside(int c, int r) const { return c >= 0 && r >= 0 && c < cols && r < rows; }
  std::size_t global(int c, int r) const { return static_cast<std::size_t>(r + r0) * cols_all + c + c0; }
  std::size_t global(std::size_t j) const {
    return global(static_cast<int>(j % cols), static_cast<int>(j / cols));
  }
};

/// Each room's cells' bounding window grown by `margin` cells (clipped to the raster); an
/// empty window for a room without cells.
std::vector<Window> room_windows(const std::vector<int>& label, int count, int cols, int rows, int margin) {
  std::vector<std::array<int, 4>> box(count, {cols, rows, -1, -1});
  for (std::size_t i = 0; i < label.size(); ++i) {
    if (label[i] < 0) continue;
    auto& b = box[label[i]];
    const int c = static_cast<int>(i % cols), r = static_cast<int>(i / cols);
    b = {std::min(b[0], c), std::min(b[1], r), std::max(b[2], c), std::max(b[3], r)};
  }
  std::vector<Window> out(count);
  for (int k = 0; k < count; ++k) {
    const auto& b = box[k];
    if (b[2] < 0) continue;
    Window& w = out[k];
    w.cols_all = cols;
    w.c0 = std::max(0, b[0] - margin);
    w.r0 = std::max(0, b[1] - margin);
    w.cols = std::min(cols - 1, b[2] + margin) - w.c0 + 1;
    w.rows = std::min(rows - 1, b[3] + margin) - w.r0 + 1;
  }
  return out;
}

/// Distance (cells) from each cell of the window to the nearest of its cells where `is_source`
/// holds (a global index); cells beyond the window are sources when `border_is_source`.
template <typename Pred>
std::vector<float> distance_in(const Window& w, Pred is_source, bool border_is_source) {
  GridFrame f;
  f.resolution = 1.0;
  f.cols = w.cols;
  f.rows = w.rows;
  std::vector<std::uint8_t> open(w.size());
  for (std::size_t j = 0; j < open.size(); ++j) open[j] = !is_source(w.global(j));
  return distance_transform(f, open, border_is_source);
}

/// Step 1: the rooms closed together with a disc of `radius` cells.
std::vector<int> close_rooms(const std::vector<int>& label, int count, int cols, int rows, double radius) {
  if (!(radius > 0.0)) return label;
  const float r = static_cast<float>(radius) + kDistanceSlack;
  const std::vector<Window> windows =
      room_windows(label, count, cols, rows, static_cast<int>(std::ceil(radius)) + 1);
  // Dilation: each unlabelled cell within the radius of a room goes to the nearest.
  std::vector<float> nearest(label.size(), std::numeric_limits<float>::infinity());
  std::vector<int> share = label;
  for (int k = 0; k < count; ++k) {
    const Window& w = windows[k];
    if (w.size() == 0) continue;
    const std::vector<float> d = distance_in(
        w, [&](std::size_t i) { return label[i] == k; }, false);
    for (std::size_t j = 0; j < d.size(); ++j) {
      const std::size_t i = w.global(j);
      if (label[i] < 0 && d[j] <= r && d[j] < nearest[i]) {
        nearest[i] = d[j];
        share[i] = k;
      }
    }
  }
  // Erosion: a cell of a room's share stays with it when nothing but that share lies within the radius.
  std::vector<int> out = label;
  for (int k = 0; k < count; ++k) {
    const Window& w = windows[k];
    if (w.size() == 0) continue;
    const std::vector<float> d = distance_in(
        w, [&](std::size_t i) { return share[i] != k; }, true);
    for (std::size_t j = 0; j < d.size(); ++j) {
      const std::size_t i = w.global(j);
      if (label[i] < 0 && share[i] == k && d[j] > r) out[i] = k;
    }
  }
  return out;
}

/// Step 2: a cell of a room 8-adjacent to a cell of an earlier room is given up.
void separate_rooms(std::vector<int>* label, int cols, int rows) {
  const std::vector<int> before = *label;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      const std::size_t i = static_cast<std::size_t>(r) * cols + c;
      const int k = before[i];
      if (k <= 0) continue;
      for (int dr = -1; dr <= 1 && (*label)[i] >= 0; ++dr) {
        for (int dc = -1; dc <= 1; ++dc) {
          const int cc = c + dc, rr = r + dr;
          if (cc < 0 || rr < 0 || cc >= cols || rr >= rows) continue;
          const int j = before[static_cast<std::size_t>(rr) * cols + cc];
          if (j >= 0 && j < k) {
            (*label)[i] = -1;
            break;
          }
        }
      }
    }
  }
}

/// Steps 3 and 5: each room keeps its largest 8-connected piece (the first of equal ones).
void keep_largest_pieces(std::vector<int>* label, int count, int cols, int rows) {
  const std::vector<Window> windows = room_windows(*label, count, cols, rows, 0);
  for (int k = 0; k < count; ++k) {
    const Window& w = windows[k];
    if (w.size() == 0) continue;
    std::vector<std::uint8_t> mask(w.size());
    for (std::size_t j = 0; j < mask.size(); ++j) mask[j] = (*label)[w.global(j)] == k;
    std::vector<std::size_t> sizes;
    const std::vector<int> piece = label_regions(mask, w.cols, w.rows, true, &sizes);
    if (sizes.size() <= 1) continue;
    const int main = static_cast<int>(std::max_element(sizes.begin(), sizes.end()) - sizes.begin());
    for (std::size_t j = 0; j < piece.size(); ++j) {
      if (piece[j] >= 0 && piece[j] != main) (*label)[w.global(j)] = -1;
    }
  }
}

/// The holes of one room in its window: 4-connected regions of other cells that do not reach
/// the window's edge.
struct Holes {
  std::vector<int> id;  ///< per window cell: its region of other cells, or -1 (the room's cells)
  std::vector<std::uint8_t> outside;     ///< per region: reaches the window's edge (or has been opened)
  std::vector<std::uint8_t> holds_room;  ///< per region: holds a cell of another room
};

Holes find_holes(const std::vector<int>& label, const Window& w, int k) {
  std::vector<std::uint8_t> other(w.size());
  for (std::size_t j = 0; j < other.size(); ++j) other[j] = label[w.global(j)] != k;
  std::vector<std::size_t> sizes;
  Holes h;
  h.id = label_regions(other, w.cols, w.rows, false, &sizes);
  h.outside.assign(sizes.size(), 0);
  h.holds_room.assign(sizes.size(), 0);
  for (int r = 0; r < w.rows; ++r) {
    for (int c = 0; c < w.cols; ++c) {
      const std::size_t j = static_cast<std::size_t>(r) * w.cols + c;
      const int id = h.id[j];
      if (id < 0) continue;
      if (c == 0 || r == 0 || c == w.cols - 1 || r == w.rows - 1) h.outside[id] = 1;
      if (label[w.global(j)] >= 0) h.holds_room[id] = 1;
    }
  }
  return h;
}

/// Opens hole `hole` of room k: the shortest 4-connected path from it through the room (and
/// through holes not yet opened) to a cell next to the outside; the room's cells on it are
/// given up, and the holes it passes become outside.
void open_hole(std::vector<int>* label, const Window& w, int k, int hole, Holes* h) {
  const std::size_t none = std::numeric_limits<std::size_t>::max();
  std::vector<std::size_t> parent(w.size(), none);
  std::deque<std::size_t> queue;
  const auto passable = [&](std::size_t j) {
    return h->id[j] < 0 || (h->id[j] != hole && !h->outside[h->id[j]]);
  };
  for (std::size_t j = 0; j < w.size(); ++j) {
    if (h->id[j] != hole) continue;
    const int c = static_cast<int>(j % w.cols), r = static_cast<int>(j / w.cols);
    for (const auto& s : kSides) {
      if (!w.inside(c + s[0], r + s[1])) continue;
      const std::size_t n = static_cast<std::size_t>(r + s[1]) * w.cols + c + s[0];
      if (h->id[n] < 0 && parent[n] == none) {
        parent[n] = n;
        queue.push_back(n);
      }
    }
  }
  std::size_t end = none;
  while (!queue.empty() && end == none) {
    const std::size_t j = queue.front();
    queue.pop_front();
    const int c = static_cast<int>(j % w.cols), r = static_cast<int>(j / w.cols);
    for (const auto& s : kSides) {
      const int cc = c + s[0], rr = r + s[1];
      if (!w.inside(cc, rr)) {
        end = j;  // beyond the raster: outside
        break;
      }
      const std::size_t n = static_cast<std::size_t>(rr) * w.cols + cc;
      if (h->id[n] >= 0 && h->outside[h->id[n]]) {
        end = j;
        break;
      }
      if (passable(n) && parent[n] == none) {
        parent[n] = j;
        queue.push_back(n);
      }
    }
  }
  if (end == none)
    throw std::logic_error("room_regions: a hole with no way out");  // the window's edge is outside
  h->outside[hole] = 1;
  for (std::size_t j = end;; j = parent[j]) {
    if (h->id[j] >= 0) h->outside[h->id[j]] = 1;
    if ((*label)[w.global(j)] == k) (*label)[w.global(j)] = -1;
    if (parent[j] == j) break;
  }
}

/// Step 4: holes without another room filled, those with one opened. Returns the slits cut.
int fill_or_open_holes(std::vector<int>* label, int count, int cols, int rows) {
  const std::vector<Window> windows = room_windows(*label, count, cols, rows, 1);
  int slits = 0;
  for (int k = 0; k < count; ++k) {
    const Window& w = windows[k];
    if (w.size() == 0) continue;
    Holes h = find_holes(*label, w, k);
    for (int hole = 0; hole < static_cast<int>(h.outside.size()); ++hole) {
      if (h.outside[hole] || !h.holds_room[hole]) continue;
      open_hole(label, w, k, hole, &h);
      ++slits;
    }
    for (std::size_t j = 0; j < w.size(); ++j) {
      const int id = h.id[j];
      if (id >= 0 && !h.outside[id]) (*label)[w.global(j)] = k;  // a hole of nothing but unlabelled cells
    }
  }
  return slits;
}

}  // namespace

MapRoomRegions room_regions(const std::vector<int>& room_of_cell, int count, int cols, int rows,
                            double closing_radius) {
  if (cols < 1 || rows < 1 || count < 0 || room_of_cell.size() != static_cast<std::size_t>(cols) * rows ||
      !(closing_radius >= 0.0))
    throw std::invalid_argument("room_regions: the labels' size disagrees with the raster");
  for (int k : room_of_cell) {
    if (k < -1 || k >= count) throw std::invalid_argument("room_regions: a room index out of range");
  }
  MapRoomRegions out;
  out.region = close_rooms(room_of_cell, count, cols, rows, closing_radius);
  separate_rooms(&out.region, cols, rows);
  keep_largest_pieces(&out.region, count, cols, rows);
  out.slits = fill_or_open_holes(&out.region, count, cols, rows);
  keep_largest_pieces(&out.region, count, cols, rows);
  out.cells.assign(count, 0);
  out.labelled_out.assign(count, 0);
  for (std::size_t i = 0; i < out.region.size(); ++i) {
    if (out.region[i] >= 0) ++out.cells[out.region[i]];
    if (room_of_cell[i] >= 0 && out.region[i] != room_of_cell[i]) ++out.labelled_out[room_of_cell[i]];
  }
  return out;
}

}  // namespace tsgraphs::map_import
