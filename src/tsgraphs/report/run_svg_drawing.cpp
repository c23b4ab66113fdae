// What the pictures of a run share (run_svg_drawing.hpp).
//
// Each picture is one <svg> whose root has a class (tsg-birdseye, tsg-side-view, tsg-timing)
// and whose <style> rules are scoped to it, with no ids, so that any number of them can be
// inlined in one HTML page. Thousands of points (traversable nodes, free space) are drawn
// as zero-length subpaths with round caps merged into one <path> per colour, thinned to
// one dot per small cell so that a page of eight pictures of a large map stays a few MB;
// the path's data-count says how many points it stands for.
#include "tsgraphs/report/run_svg_drawing.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace tsgraphs::report::run_drawing {
namespace {

constexpr const char* kHalo = "#ffffff";
constexpr const char* kFont = "DejaVu Sans, Helvetica, Arial, sans-serif";

// Room colours: rooms cyan-ish, corridors orange-ish (as in map.ply), each room's hue moved
// within its band by the golden ratio of its id so that neighbours differ.
constexpr double kRoomHueDeg = 188.0;
constexpr double kCorridorHueDeg = 30.0;
constexpr double kRoomHueSpreadDeg = 36.0;
constexpr double kCorridorHueSpreadDeg = 22.0;
constexpr double kGoldenRatio = 0.6180339887498949;
constexpr double kRoomSaturation = 0.78;
constexpr double kRoomLightness = 0.44;

}  // namespace

bool is_corridor(const RunView::Room& r) { return r.kind == "corridor"; }

std::string room_colour(const RunView::Room& r) {
  const double spread = std::fmod(std::abs(static_cast<double>(r.id)) * kGoldenRatio, 1.0) - 0.5;
  const double hue = is_corridor(r) ? kCorridorHueDeg + kCorridorHueSpreadDeg * spread
                                    : kRoomHueDeg + kRoomHueSpreadDeg * spread;
  return svg::hsl_colour(hue, kRoomSaturation, kRoomLightness);
}

std::string xy(const Vec2& p) { return num(p.x()) + "," + num(p.y()); }
std::string points_attr(const Frame& f, const std::vector<Vec2>& pts) {
  std::string s;
  for (const Vec2& p : pts) s += (s.empty() ? "" : " ") + xy(f.px(p));
  return s;
}

/// Keeps a vertex only `step` or more from the last one kept (and always the last).
std::vector<Vec2> thinned(const std::vector<Vec2>& pts, double step) {
  std::vector<Vec2> out;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    if (out.empty() || (pts[i] - out.back()).norm() >= step || i + 1 == pts.size()) out.push_back(pts[i]);
  }
  return out;
}

/// "<svg ...>", its <title> and a <style> whose rules are prefixed with the root class.
/// The legends' samples use "key-" classes styled like what they stand for, so that
/// counting an element class counts what the picture shows, not its legend.
std::string open_svg(double w, double h, const std::string& root, const std::string& title,
                     const std::vector<std::pair<std::string, std::string>>& rules) {
  std::string out = "<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"" + root + "\" width=\"" + num(w) +
                    "\" height=\"" + num(h) + "\" viewBox=\"0 0 " + num(w) + " " + num(h) + "\">\n";
  out += "<title>" + xml_escape(title) + "</title>\n<style>\n";
  const std::vector<std::pair<std::string, std::string>> common = {
      {"text", std::string("font-family: ") + kFont + "; fill: " + kInk + ";"},
      {".title", "font-size: 15px; font-weight: bold;"},
      {".subtitle", std::string("font-size: 11px; fill: ") + kMutedInk + ";"},
      {".legend-text", "font-size: 11px;"},
      {".scale-text", "font-size: 10px;"},
      {".halo",
       std::string("stroke: ") + kHalo + "; stroke-width: 3px; stroke-linejoin: round; paint-order: stroke;"},
  };
  for (const auto* list : {&common, &rules}) {
    for (const auto& [selectors, declarations] : *list) {
      // Each selector of a list ("a, b") scoped to the root.
      std::string scoped;
      for (std::size_t at = 0; at < selectors.size();) {
        std::size_t end = selectors.find(',', at);
        if (end == std::string::npos) end = selectors.size();
        const std::size_t first = selectors.find_first_not_of(' ', at);
        scoped += (scoped.empty() ? "." : ", .") + root + " " + selectors.substr(first, end - first);
        at = end + 1;
      }
      out += scoped + " { " + declarations + " }\n";
    }
  }
  out += "</style>\n";
  out += "<rect class=\"background\" x=\"0\" y=\"0\" width=\"" + num(w) + "\" height=\"" + num(h) +
         "\" fill=\"" + kBackground + "\"/>\n";
  return out;
}

std::size_t legend_columns(double width) {
  return static_cast<std::size_t>(std::max(1.0, std::floor(width / kLegendColumnWidth)));
}

double legend_height(std::size_t entries, double width) {
  const std::size_t columns = legend_columns(width);
  return static_cast<double>((entries + columns - 1) / columns) * kLegendRow;
}
namespace {

std::string replace_all(std::string s, const std::string& from, const std::string& to) {
  for (std::size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size())) {
    s.replace(at, from.size(), to);
  }
  return s;
}

}  // namespace

std::string draw_legend(const std::vector<LegendEntry>& entries, double x, double y, double width) {
  const std::size_t columns = legend_columns(width);
  std::string out = "<g class=\"legend\">\n";
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const double ex = x + static_cast<double>(i % columns) * kLegendColumnWidth;
    const double ey = y + (static_cast<double>(i / columns) + 0.5) * kLegendRow;
    std::string s = entries[i].swatch;
    s = replace_all(s, "{X0}", num(ex));
    s = replace_all(s, "{X1}", num(ex + kLegendSwatch));
    s = replace_all(s, "{XM}", num(ex + 0.5 * kLegendSwatch));
    s = replace_all(s, "{Y}", num(ey));
    out += s + "\n";
    out += text(ex + kLegendSwatch + kLegendGap, ey + kTextBaselineShift, "legend-text", entries[i].what);
  }
  out += "</g>\n";
  return out;
}

/// A horizontal sample line of class `cls` for the legend.
std::string key_line(const std::string& cls, const std::string& attrs) {
  return "<line class=\"" + cls + "\"" + attrs + " x1=\"{X0}\" y1=\"{Y}\" x2=\"{X1}\" y2=\"{Y}\"/>";
}

/// A sample dot (zero-length path) of class `cls`.
std::string key_dot(const std::string& cls, const std::string& attrs) {
  return "<path class=\"" + cls + "\"" + attrs + " d=\"M{XM},{Y}h0\"/>";
}

std::vector<std::pair<std::string, std::string>> axes_style(const std::string& value,
                                                            const std::string& along) {
  return {
      {".frame", std::string("fill: none; stroke: ") + kFrameStroke + "; stroke-width: 1;"},
      {".grid", std::string("stroke: ") + kGrid + "; stroke-width: 1;"},
      {".tick", std::string("stroke: ") + kInk + "; stroke-width: 1;"},
      {".tick-label", "font-size: 10px;"},
      {".tick-label." + value, "text-anchor: end;"},
      {".tick-label." + along, "text-anchor: middle;"},
      {".axis-title", "font-size: 11px;"},
  };
}

std::string headings(const std::string& title, const std::string& subtitle) {
  return text(kPageMargin, kPageMargin + kTitleBaseline, "title", title) +
         text(kPageMargin, kPageMargin + kSubtitleBaseline, "subtitle", subtitle);
}

std::string x_grid_line(double x, double top, double bottom) {
  return "<line class=\"grid\" x1=\"" + num(x) + "\" y1=\"" + num(top) + "\" x2=\"" + num(x) + "\" y2=\"" +
         num(bottom) + "\"/>\n" + "<line class=\"tick\" x1=\"" + num(x) + "\" y1=\"" + num(bottom) +
         "\" x2=\"" + num(x) + "\" y2=\"" + num(bottom + kTickLength) + "\"/>\n";
}

std::string y_grid_line(double y, double left, double right) {
  return "<line class=\"grid\" x1=\"" + num(left) + "\" y1=\"" + num(y) + "\" x2=\"" + num(right) +
         "\" y2=\"" + num(y) + "\"/>\n" + "<line class=\"tick\" x1=\"" + num(left - kTickLength) +
         "\" y1=\"" + num(y) + "\" x2=\"" + num(left) + "\" y2=\"" + num(y) + "\"/>\n";
}

/// A step of 1, 2 or 5 times a power of ten giving about `ticks` ticks over `range`.
double nice_step(double range, int ticks) {
  const double raw = range / std::max(ticks, 1);
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  const double f = raw / magnitude;
  return (f < 1.5 ? 1.0 : f < 3.5 ? 2.0 : f < 7.5 ? 5.0 : 10.0) * magnitude;
}

/// Multiples of `step` within [lo, hi] (to rounding).
std::vector<double> ticks_between(double lo, double hi, double step) {
  std::vector<double> out;
  for (long k = std::lround(std::ceil(lo / step - kEps)); static_cast<double>(k) * step <= hi + kEps * step;
       ++k) {
    out.push_back(static_cast<double>(k) * step);
  }
  return out;
}

}  // namespace tsgraphs::report::run_drawing
