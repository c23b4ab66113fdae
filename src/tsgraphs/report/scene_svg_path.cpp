// The scene picture's panels, the first lap of the path on a level (coloured by time, with
// arrowheads, its start and end) and the names placed during the panel.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "tsgraphs/report/scene_drawing.hpp"

namespace tsgraphs::report::scene_drawing {

void SceneDrawer::draw_path(const Frame& f, int level) {
  if (path_.empty()) return;
  out_ += "<g class=\"layer-path\">\n";
  const double duration = std::max(path_.back().t, kEps);
  // Runs of consecutive samples on this level (a path that changes level leaves one run
  // and starts another on the other panel).
  std::vector<std::pair<std::size_t, std::size_t>> runs;  // [first, last]
  for (std::size_t i = 0; i < path_.size(); ++i) {
    if (path_[i].level != level) continue;
    if (!runs.empty() && runs.back().second + 1 == i) {
      runs.back().second = i;
    } else {
      runs.emplace_back(i, i);
    }
  }
  for (const auto& [first, last] : runs) {
    out_ += "<polyline class=\"path-casing\" points=\"" + path_points(f, first, last) + "\"/>\n";
  }
  auto chunk_of = [&](std::size_t i) {
    return static_cast<long>(std::floor(path_[i].t / kPathChunkS + kEps));
  };
  for (const auto& [first, last] : runs) {
    if (first == last) {
      out_ += "<polyline class=\"path\" stroke=\"" + path_colour(path_[first].t / duration) + "\" points=\"" +
              path_points(f, first, last) + "\"/>\n";
      continue;
    }
    // One polyline per chunk, ending on the next chunk's first sample so they join.
    for (std::size_t i = first; i < last;) {
      std::size_t j = i + 1;
      while (j < last && chunk_of(j) == chunk_of(i)) ++j;
      const double mid = 0.5 * (path_[i].t + path_[j].t);
      out_ += "<polyline class=\"path\" stroke=\"" + path_colour(mid / duration) + "\" points=\"" +
              path_points(f, i, j) + "\"/>\n";
      i = j;
    }
  }
  draw_arrows(f, level, duration);
  out_ += "</g>\n";
}

void SceneDrawer::draw_path_ends(const Frame& f, int level) {
  if (path_.empty()) return;
  out_ += "<g class=\"layer-path-ends\">\n";
  const PathSample& s0 = path_.front();
  const PathSample& s1 = path_.back();
  if (s1.level == level && (s1.xy - s0.xy).norm() >= kEndMinDistanceM) {
    const Vec2 c = f.px(s1.xy);
    out_ += "<rect class=\"end\" stroke=\"" + path_colour(1.0) + "\" x=\"" + num(c.x() - kEndHalfSize) +
            "\" y=\"" + num(c.y() - kEndHalfSize) + "\" width=\"" + num(2.0 * kEndHalfSize) + "\" height=\"" +
            num(2.0 * kEndHalfSize) + "\"/>\n";
  }
  if (s0.level == level) {
    const Vec2 c = f.px(s0.xy);
    out_ += "<circle class=\"start\" stroke=\"" + path_colour(0.0) + "\" cx=\"" + num(c.x()) + "\" cy=\"" +
            num(c.y()) + "\" r=\"" + num(kStartRadius) + "\"/>\n";
  }
  out_ += "</g>\n";
}

std::string SceneDrawer::path_points(const Frame& f, std::size_t first, std::size_t last) const {
  std::string s;
  for (std::size_t i = first; i <= last; ++i) {
    if (i > first && (path_[i].xy - path_[i - 1].xy).norm() < kEps) continue;  // turning in place
    s += (s.empty() ? "" : " ") + xy(f.px(path_[i].xy));
  }
  if (s.find(' ') == std::string::npos) s += " " + s;  // a single point still draws a dot
  return s;
}

std::string SceneDrawer::arrowhead_points(const Vec2& c, const Vec2& d) {
  const Vec2 n = left_normal(d);
  const Vec2 tip = c + 0.5 * kArrowLength * d, back = c - 0.5 * kArrowLength * d;
  return xy(tip) + " " + xy(back + kArrowHalfWidth * n) + " " + xy(back - kArrowHalfWidth * n);
}

void SceneDrawer::draw_arrows(const Frame& f, int level, double duration) {
  std::size_t i = 0;
  for (double at = 0.5 * kArrowSpacingM; at < path_.back().s; at += kArrowSpacingM) {
    while (i + 1 < path_.size() && path_[i].s < at) ++i;
    const PathSample& p = path_[i];
    if (p.level != level) continue;
    const Vec2 d(std::cos(p.yaw), -std::sin(p.yaw));  // page y points down
    out_ += "<polygon class=\"arrow\" fill=\"" + path_colour(p.t / duration) + "\" points=\"" +
            arrowhead_points(f.px(p.xy), d) + "\"/>\n";
  }
}

void SceneDrawer::draw_labels(const Frame& f, int level) {
  out_ += "<g class=\"layer-labels\">\n";
  const bool start_here = !path_.empty() && path_.front().level == level;
  const Vec2 start = start_here ? f.px(path_.front().xy) : Vec2::Zero();
  for (const Label& l : labels_) {
    Vec2 p = f.px(l.at);
    const double half_width = 0.5 * kLabelCharWidth * static_cast<double>(l.text.size()) + kStartRadius;
    if (start_here && std::abs(p.x() - start.x()) < half_width &&
        std::abs(p.y() - start.y()) < 0.5 * kLabelLineHeight + kStartRadius) {
      p.y() = start.y() + kLabelMarkerShift;
    }
    out_ += "<text class=\"label " + l.cls + "\" x=\"" + num(p.x()) + "\" y=\"" +
            num(p.y() + kLabelBaseline) + "\">" + xml_escape(l.text) + "</text>\n";
  }
  out_ += "</g>\n";
}

}  // namespace tsgraphs::report::scene_drawing
