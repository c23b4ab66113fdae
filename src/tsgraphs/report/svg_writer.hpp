#pragma once
/// Internal to the report module: the text primitives every SVG and HTML writer here shares,
/// so that all pictures print numbers and escape text the same way (locale-free, fixed
/// decimals, deterministic bytes).
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <string_view>

#include "tsgraphs/core/polygon.hpp"

namespace tsgraphs::report::svg {

/// Fixed two-decimal number, independent of the C locale; never "-0.00".
inline std::string num(double v) {
  if (!std::isfinite(v)) v = 0.0;
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed, 2);
  std::string s(buf, r.ptr);
  if (s == "-0.00") s = "0.00";
  return s;
}

/// As `num`, without trailing zeros: for numbers in prose ("every 3 m").
inline std::string short_num(double v) {
  std::string s = num(v);
  while (s.back() == '0') s.pop_back();
  if (s.back() == '.') s.pop_back();
  return s;
}

/// Length of the valid UTF-8 sequence starting at s[i], or 0.
inline std::size_t utf8_length(std::string_view s, std::size_t i) {
  const auto c = static_cast<unsigned char>(s[i]);
  std::size_t n = c < 0x80 ? 1 : (c >> 5) == 0x6 ? 2 : (c >> 4) == 0xE ? 3 : (c >> 3) == 0x1E ? 4 : 0;
  if (n == 0 || i + n > s.size()) return 0;
  for (std::size_t k = 1; k < n; ++k) {
    if ((static_cast<unsigned char>(s[i + k]) >> 6) != 0x2) return 0;
  }
  return n;
}

/// Text safe inside an element or an attribute (of SVG or HTML): markup characters escaped,
/// characters XML forbids (control codes, broken UTF-8) replaced by '?'.
inline std::string xml_escape(std::string_view text) {
  std::string out;
  for (std::size_t i = 0; i < text.size();) {
    const char c = text[i];
    switch (c) {
      case '&':
        out += "&amp;";
        ++i;
        continue;
      case '<':
        out += "&lt;";
        ++i;
        continue;
      case '>':
        out += "&gt;";
        ++i;
        continue;
      case '"':
        out += "&quot;";
        ++i;
        continue;
      case '\'':
        out += "&apos;";
        ++i;
        continue;
      default:
        break;
    }
    const std::size_t n = utf8_length(text, i);
    const bool control = n == 1 && static_cast<unsigned char>(c) < 0x20 && c != '\t';
    if (n == 0 || control) {
      out += '?';
      ++i;
    } else {
      out.append(text.substr(i, n));
      i += n;
    }
  }
  return out;
}

/// "#rrggbb" of channels in [0, 255] (rounded, clamped).
inline std::string hex_colour(double r, double g, double b) {
  static const char* kDigits = "0123456789abcdef";
  std::string s = "#";
  for (double v : {r, g, b}) {
    const int i = std::clamp(static_cast<int>(std::lround(v)), 0, 255);
    s += kDigits[i >> 4];
    s += kDigits[i & 15];
  }
  return s;
}

/// "#rrggbb" of a hue (degrees, any value), saturation and lightness in [0, 1].
inline std::string hsl_colour(double hue_deg, double saturation, double lightness) {
  double h = std::fmod(hue_deg, 360.0) / 60.0;
  if (h < 0.0) h += 6.0;
  const double c = (1.0 - std::abs(2.0 * lightness - 1.0)) * saturation;
  const double x = c * (1.0 - std::abs(std::fmod(h, 2.0) - 1.0));
  const double m = lightness - 0.5 * c;
  double r = 0, g = 0, b = 0;
  switch (static_cast<int>(h)) {
    case 0:
      r = c, g = x;
      break;
    case 1:
      r = x, g = c;
      break;
    case 2:
      g = c, b = x;
      break;
    case 3:
      g = x, b = c;
      break;
    case 4:
      r = x, b = c;
      break;
    default:
      r = c, b = x;
      break;
  }
  return hex_colour(255.0 * (r + m), 255.0 * (g + m), 255.0 * (b + m));
}

/// Axis-aligned extent in metres.
struct Extent {
  double min_x = std::numeric_limits<double>::infinity(), min_y = min_x;
  double max_x = -min_x, max_y = -min_x;
  void add(const Vec2& p) {
    min_x = std::min(min_x, p.x()), max_x = std::max(max_x, p.x());
    min_y = std::min(min_y, p.y()), max_y = std::max(max_y, p.y());
  }
  void add(const Polygon2& poly) {
    for (const Vec2& p : poly) add(p);
  }
  bool empty() const { return !(min_x <= max_x); }
};

/// The larger side of a drawing at most, px: browsers stop drawing far beyond (Chromium at
/// 32,767 px), and a building shown larger is no more readable.
inline constexpr double kMaxDrawingPx = 16384.0;

/// px per metre for a drawing of `e`: `preferred`, or less when the drawing's larger side would
/// exceed kMaxDrawingPx at it (a run kilometres long; a building keeps `preferred`).
inline double drawing_scale(const Extent& e, double preferred) {
  const double side = std::max(e.max_x - e.min_x, e.max_y - e.min_y);
  return side * preferred > kMaxDrawingPx ? kMaxDrawingPx / side : preferred;
}

/// A text element of class `cls` with its baseline starting at (x, y).
inline std::string text(double x, double y, const std::string& cls, const std::string& what) {
  return "<text class=\"" + cls + "\" x=\"" + num(x) + "\" y=\"" + num(y) + "\">" + xml_escape(what) +
         "</text>\n";
}

/// How a scale bar looks: `metres` long, alternating ink and paper metres, labelled 0, 1
/// and the length below it.
struct ScaleBarStyle {
  double px_per_metre = 40.0;
  int metres = 5;
  double thickness = 6.0;   ///< of the bar, px
  double text_gap = 12.0;   ///< between the bar and its numbers' baseline
  double text_shift = 3.0;  ///< numbers start this far left of their tick
  const char* ink = "#222222";
  const char* paper = "#ffffff";
};

/// A scale bar whose top left corner is at (x, y), in a group of class "scale-bar"; its
/// numbers have class "scale-text".
inline std::string scale_bar(double x, double y, const ScaleBarStyle& s) {
  std::string out = "<g class=\"scale-bar\">\n";
  for (int m = 0; m < s.metres; ++m) {
    out += "<rect x=\"" + num(x + m * s.px_per_metre) + "\" y=\"" + num(y) + "\" width=\"" +
           num(s.px_per_metre) + "\" height=\"" + num(s.thickness) + "\" fill=\"" +
           (m % 2 == 0 ? s.ink : s.paper) + "\" stroke=\"" + s.ink + "\" stroke-width=\"0.8\"/>\n";
  }
  const double ty = y + s.thickness + s.text_gap;
  out += text(x - s.text_shift, ty, "scale-text", "0");
  out += text(x + s.px_per_metre - s.text_shift, ty, "scale-text", "1");
  out +=
      text(x + s.metres * s.px_per_metre - s.text_shift, ty, "scale-text", std::to_string(s.metres) + " m");
  out += "</g>\n";
  return out;
}

}  // namespace tsgraphs::report::svg
