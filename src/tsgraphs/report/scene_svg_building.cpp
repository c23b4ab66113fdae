// The scene picture's panels, what stands on a level: the slab and its voids, rooms, ramps,
// voxel maps, boxes, people, walls with their doors and windows, and railings.
#include <algorithm>
#include <cstddef>
#include <limits>
#include <string>

#include "tsgraphs/report/scene_drawing.hpp"

namespace tsgraphs::report::scene_drawing {

void SceneDrawer::draw_slab(const Frame& f, int level) {
  const scene::Level& l = scene_.levels[level];
  out_ += "<g class=\"layer-slab\">\n";
  out_ += "<polygon class=\"slab\" points=\"" + points_attr(f, l.slab) + "\"/>\n";
  for (const Polygon2& v : l.voids) {
    out_ += "<polygon class=\"void\" points=\"" + points_attr(f, v) + "\"/>\n";
    const Vec2 at = label_point(v);
    const bool under_ramp = std::any_of(scene_.ramps.begin(), scene_.ramps.end(), [&](const scene::Ramp& r) {
      return (r.from_level == level || r.to_level == level) && contains(r.polygon, at);
    });
    if (!under_ramp) labels_.push_back({at, "void", "void-name"});
  }
  out_ += "</g>\n";
}

void SceneDrawer::draw_rooms(const Frame& f, int level) {
  out_ += "<g class=\"layer-rooms\">\n";
  for (std::size_t i = 0; i < scene_.rooms.size(); ++i) {
    const scene::Room& r = scene_.rooms[i];
    if (r.level != level) continue;
    const std::string colour = room_colour(i);
    out_ += "<polygon class=\"room\" fill=\"" + colour + "\" stroke=\"" + colour + "\" points=\"" +
            points_attr(f, r.polygon) + "\"/>\n";
    labels_.push_back({label_point(r.polygon), r.name, "room-name"});
  }
  out_ += "</g>\n";
}

void SceneDrawer::draw_ramps(const Frame& f, int level) {
  out_ += "<g class=\"layer-ramps\">\n";
  for (std::size_t i = 0; i < scene_.ramps.size(); ++i) {
    const scene::Ramp& r = scene_.ramps[i];
    if (r.from_level != level && r.to_level != level) continue;
    const Vec2 up = ramp_uphill(scene_, r);
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const Vec2& q : r.polygon) lo = std::min(lo, q.dot(up)), hi = std::max(hi, q.dot(up));
    const Vec2 c = label_point(r.polygon);
    const Vec2 across = c - c.dot(up) * up;  // the centre line's offset from the origin
    const Vec2 low = across + lo * up, high = across + hi * up;
    const std::string id = "ramp-" + std::to_string(i) + "-on-" + std::to_string(level);
    out_ += "<linearGradient id=\"" + id + "\" gradientUnits=\"userSpaceOnUse\" x1=\"" + num(f.px(low).x()) +
            "\" y1=\"" + num(f.px(low).y()) + "\" x2=\"" + num(f.px(high).x()) + "\" y2=\"" +
            num(f.px(high).y()) + "\"><stop offset=\"0.00\" stop-color=\"" + kRampLow +
            "\"/><stop offset=\"1.00\" stop-color=\"" + kRampHigh + "\"/></linearGradient>\n";
    out_ +=
        "<polygon class=\"ramp\" fill=\"url(#" + id + ")\" points=\"" + points_attr(f, r.polygon) + "\"/>\n";
    const double half = 0.5 * kRampArrowFraction * (hi - lo);
    out_ +=
        "<path class=\"ramp-arrow\" d=\"" + arrow_path(f.px(c - half * up), f.px(c + half * up)) + "\"/>\n";
    // The label stands where one steps onto the ramp from this level.
    const int other = r.from_level == level ? r.to_level : r.from_level;
    const bool here_low = scene_.levels[level].elevation <= scene_.levels[other].elevation;
    const Vec2 entry = here_low ? Vec2(low - kRampLabelGapM * up) : Vec2(high + kRampLabelGapM * up);
    labels_.push_back(
        {entry, "ramp to " + scene_.levels[other].name + (here_low ? " (up)" : " (down)"), "ramp-name"});
  }
  out_ += "</g>\n";
}

std::string SceneDrawer::arrow_path(const Vec2& a, const Vec2& b) {
  const Vec2 d = (b - a).norm() > kEps ? Vec2((b - a).normalized()) : Vec2(1.0, 0.0);
  const Vec2 n = left_normal(d);
  const Vec2 h1 = b - kRampArrowHead * d + 0.6 * kRampArrowHead * n;
  const Vec2 h2 = b - kRampArrowHead * d - 0.6 * kRampArrowHead * n;
  return "M" + xy(a) + " L" + xy(b) + " M" + xy(h1) + " L" + xy(b) + " L" + xy(h2);
}

void SceneDrawer::draw_voxels(const Frame& f, int level) {
  out_ += "<g class=\"layer-voxels\">\n";
  for (const VoxelFootprint& v : voxels_) {
    if (v.level != level || v.cells.empty()) continue;
    std::string d;
    for (auto it = v.cells.begin(); it != v.cells.end();) {
      const long row = it->first, first = it->second;
      long last = first;
      for (++it; it != v.cells.end() && it->first == row && it->second == last + 1; ++it) ++last;
      const Vec2 a = f.px(Vec2((first - 0.5) * v.cell, (row + 0.5) * v.cell));
      const Vec2 b = f.px(Vec2((last + 0.5) * v.cell, (row - 0.5) * v.cell));
      d += "M" + xy(a) + "h" + num(b.x() - a.x()) + "v" + num(b.y() - a.y()) + "h" + num(a.x() - b.x()) + "z";
    }
    out_ += "<path class=\"voxels\" d=\"" + d + "\"/>\n";
  }
  out_ += "</g>\n";
}

void SceneDrawer::draw_boxes(const Frame& f, int level) {
  out_ += "<g class=\"layer-boxes\">\n";
  for (const scene::Box& b : scene_.boxes) {
    if (b.level != level) continue;
    if (b.label == scene::kDoorLeafLabel) {  // a door's own leaf, drawn as the door symbol is
      out_ += "<polygon class=\"door leaf\" points=\"" + points_attr(f, box_corners(b)) + "\"/>\n";
      continue;
    }
    out_ += "<polygon class=\"box\" points=\"" + points_attr(f, box_corners(b)) + "\"/>\n";
    if (!b.label.empty()) labels_.push_back({0.5 * (b.min.head<2>() + b.max.head<2>()), b.label, "box-name"});
  }
  out_ += "</g>\n";
}

void SceneDrawer::draw_people(const Frame& f, int level) {
  out_ += "<g class=\"layer-people\">\n";
  for (const scene::Person& p : scene_.people) {
    if (p.level != level) continue;
    out_ += "<polyline class=\"person\" points=\"" + points_attr(f, p.path) + "\"/>\n";
    const Vec2 c = f.px(p.path.front());
    out_ += "<circle class=\"person-start\" cx=\"" + num(c.x()) + "\" cy=\"" + num(c.y()) + "\" r=\"" +
            num(p.radius * scale_) + "\"/>\n";
  }
  out_ += "</g>\n";
}

void SceneDrawer::draw_walls(const Frame& f, int level) {
  out_ += "<g class=\"layer-walls\">\n";
  for (const char* kind : {"header", "sill", "full"}) {
    for (const scene::Wall& w : scene_.walls) {
      if (w.level != level) continue;
      for (const scene::WallPiece& piece : scene::wall_pieces(w)) {
        if (piece_kind(w, piece) != kind) continue;
        out_ += std::string("<polygon class=\"wall ") + kind + "\" points=\"" +
                points_attr(f, strip(w.from, w.to, piece.s0, piece.s1, w.thickness)) + "\"/>\n";
      }
    }
  }
  for (const scene::Wall& w : scene_.walls) {
    if (w.level != level) continue;
    for (const scene::Opening& o : w.openings) {
      if (o.sill > 0.0)
        out_ += window(f, w, o);
      else if (!has_leaf(w, o))
        out_ += door(f, w, o);  // a door whose leaf is in the scene shows that
    }
  }
  out_ += "</g>\n";
}

bool SceneDrawer::has_leaf(const scene::Wall& w, const scene::Opening& o) const {
  const Vec2 c = w.from + o.at * (w.to - w.from).normalized();
  for (const scene::Box& b : scene_.boxes) {
    if (b.level != w.level || b.label != scene::kDoorLeafLabel) continue;
    for (const Vec2& p : box_corners(b)) {
      if ((p - c).norm() <= 0.5 * o.width + w.thickness) return true;  // its hinge is at a jamb
    }
  }
  return false;
}

std::string SceneDrawer::piece_kind(const scene::Wall& w, const scene::WallPiece& p) {
  if (p.z0 > kEps) return "header";
  return p.z1 < w.height - kEps ? "sill" : "full";
}

std::string SceneDrawer::door(const Frame& f, const scene::Wall& w, const scene::Opening& o) {
  const Vec2 d = (w.to - w.from).normalized();
  const Vec2 hinge = w.from + (o.at - 0.5 * o.width) * d;
  const Vec2 open = f.px(hinge + o.width * left_normal(d));
  const Vec2 jamb = f.px(w.from + (o.at + 0.5 * o.width) * d);
  const Vec2 h = f.px(hinge);
  const Vec2 a = open - h, b = jamb - h;
  const int sweep = a.x() * b.y() - a.y() * b.x() > 0.0 ? 1 : 0;  // turning direction on the page
  const std::string r = num(o.width * f.scale);
  return "<path class=\"door\" d=\"M" + xy(h) + " L" + xy(open) + " A" + r + "," + r + " 0 0," +
         std::to_string(sweep) + " " + xy(jamb) + "\"/>\n";
}

std::string SceneDrawer::window(const Frame& f, const scene::Wall& w, const scene::Opening& o) {
  const Vec2 d = (w.to - w.from).normalized();
  const Vec2 a = f.px(w.from + (o.at - 0.5 * o.width) * d), b = f.px(w.from + (o.at + 0.5 * o.width) * d);
  return "<line class=\"window\" x1=\"" + num(a.x()) + "\" y1=\"" + num(a.y()) + "\" x2=\"" + num(b.x()) +
         "\" y2=\"" + num(b.y()) + "\"/>\n";
}

void SceneDrawer::draw_railings(const Frame& f, int level) {
  out_ += "<g class=\"layer-railings\">\n";
  for (const scene::Railing& r : scene_.railings) {
    if (r.level != level) continue;
    const Vec2 a = f.px(r.from), b = f.px(r.to);
    const std::string ends = "x1=\"" + num(a.x()) + "\" y1=\"" + num(a.y()) + "\" x2=\"" + num(b.x()) +
                             "\" y2=\"" + num(b.y()) + "\"";
    if (r.style != scene::RailingStyle::kBars) {
      const double width = std::max(scene::RailingGeometry::kSolidThickness * scale_, kMinRailingWidth);
      const char* cls = r.style == scene::RailingStyle::kGlass ? "railing glass" : "railing solid";
      out_ += std::string("<line class=\"") + cls + "\" " + ends + " stroke-width=\"" + num(width) + "\"/>\n";
    } else {
      out_ += "<g class=\"railing bars\">" + bars_lines(ends) + "</g>\n";
    }
  }
  out_ += "</g>\n";
}

std::string SceneDrawer::bars_lines(const std::string& ends) {
  return "<line " + ends + " stroke-width=\"" + num(kBarsRailWidth) + "\"/><line " + ends +
         " stroke-width=\"" + num(kBarsDotSize) + "\" stroke-linecap=\"round\" stroke-dasharray=\"0.01 " +
         num(kBarsDotSpacing) + "\"/>";
}

}  // namespace tsgraphs::report::scene_drawing
