#include "tsgraphs/generator/generator_storeys.hpp"

#include <algorithm>
#include <cmath>

#include "tsgraphs/generator/building_styles.hpp"

namespace tsgraphs::generator::internal {
namespace {

// Storeys.
constexpr double kCeilingMin = 2.6;  // m: ceiling heights
constexpr double kCeilingMax = 3.4;
constexpr double kInteriorWallMin = 0.1;  // m: wall thicknesses
constexpr double kInteriorWallMax = 0.2;
constexpr double kFacadeMin = 0.2;
constexpr double kFacadeMax = 0.3;
constexpr double kGlassTransmissionMin = 0.5;  // glass railings let this share of rays through
constexpr double kGlassTransmissionMax = 0.9;

// Ramps between storeys (multi_storey).
constexpr double kRampSlopeMin =
    0.16;  // rise per run: 9 to 12 degrees (a robot's ramp, steeper than a wheelchair's)
constexpr double kRampSlopeMax = 0.21;
constexpr double kRampWidthMin = 1.8;  // m
constexpr double kRampWidthMax = 2.4;
constexpr double kGalleryMin = 1.6;  // m: the corridor along a ramp
constexpr double kGalleryMax = 2.6;
constexpr double kRampEndMin = 3.0;  // m of storey beyond each end of a ramp

struct StyleSize {
  double w_lo, w_hi, h_lo, h_hi;
};
StyleSize size_of(const std::string& style, double scale) {
  StyleSize z = style == "office"      ? StyleSize{14, 28, 9, 20}
                : style == "atrium"    ? StyleSize{18, 30, 16, 24}
                : style == "library"   ? StyleSize{18, 32, 14, 22}
                : style == "open_plan" ? StyleSize{20, 40, 15, 30}
                                       : StyleSize{14, 22, 14, 18};  // irregular: its second wing
  // Scaled down, but never below what the style needs.
  const Vec2 m = minimum_region(style);
  return {std::max(m.x(), z.w_lo * scale), std::max(m.x(), z.w_hi * scale), std::max(m.y(), z.h_lo * scale),
          std::max(m.y(), z.h_hi * scale)};
}

void fill(const std::string& style, FloorPlan* plan, const Region& r, Rng& rng, const std::string& prefix,
          IrregularVariant variant = IrregularVariant::kAny) {
  if (style == "office")
    fill_office(plan, r, rng, prefix);
  else if (style == "atrium")
    fill_atrium(plan, r, rng, prefix);
  else if (style == "library")
    fill_library(plan, r, rng, prefix);
  else if (style == "open_plan")
    fill_open_plan(plan, r, rng, prefix);
  else
    fill_irregular(plan, r, rng, prefix, variant);
}

/// Wings side by side along x, their floors at y = 0: a staircase outline.
Polygon2 staircase(const std::vector<Region>& wings) {
  Polygon2 pts = {wings.front().lo, {wings.back().hi.x(), 0.0}};
  for (int i = static_cast<int>(wings.size()) - 1; i >= 0; --i) {
    pts.push_back({wings[i].hi.x(), wings[i].hi.y()});
    pts.push_back({wings[i].lo.x(), wings[i].hi.y()});
  }
  Polygon2 out;
  for (const Vec2& p : pts) {
    if (out.empty() || (out.back() - p).norm() > 1e-9) out.push_back(p);
  }
  while (out.size() > 1 && (out.back() - out.front()).norm() < 1e-9) out.pop_back();
  Polygon2 simple;
  for (std::size_t i = 0; i < out.size(); ++i) {
    const Vec2 d0 = out[i] - out[(i + out.size() - 1) % out.size()], d1 = out[(i + 1) % out.size()] - out[i];
    if (std::abs(d0.x() * d1.y() - d0.y() * d1.x()) > 1e-12) simple.push_back(out[i]);
  }
  return simple;
}

FloorPlanRules draw_rules(Rng& rng) {
  FloorPlanRules r;
  r.interior_wall = rng.uniform(kInteriorWallMin, kInteriorWallMax);
  r.exterior_wall = rng.uniform(kFacadeMin, kFacadeMax);
  const double u = rng.unit();
  r.railing = u < 1.0 / 3   ? scene::RailingStyle::kSolid
              : u < 2.0 / 3 ? scene::RailingStyle::kBars
                            : scene::RailingStyle::kGlass;
  r.glass_transmission = rng.uniform(kGlassTransmissionMin, kGlassTransmissionMax);
  return r;
}

/// An open lobby under an atrium: the storey below that its void shows.
Storey lobby_below(const Region& r, const FloorPlanRules& rules, double ceiling) {
  Storey s;
  s.name = "L0";
  s.plan.rules = rules;
  s.plan.ground_truth = false;
  s.plan.add_rect("lobby", SpaceKind::kHall, r.lo, r.hi, Furnishing::kLobby);
  s.slab = rect_polygon(r.lo, r.hi);
  s.ceiling = ceiling;
  s.walked = false;
  return s;
}

Building single_wing(const std::string& style, double scale, bool realistic, Rng& rng) {
  const StyleSize z = size_of(style, scale);
  const Region r{{0, 0}, {rng.uniform(z.w_lo, z.w_hi), rng.uniform(z.h_lo, z.h_hi)}};
  const FloorPlanRules rules = draw_rules(rng);
  const double ceiling = rng.uniform(kCeilingMin, kCeilingMax);
  Building b;
  if (style == "atrium") b.storeys.push_back(lobby_below(r, rules, rng.uniform(kCeilingMin, kCeilingMax)));
  Storey s;
  s.name = "L" + std::to_string(b.storeys.size());
  s.plan.rules = rules;
  s.plan.realistic = realistic;
  s.slab = rect_polygon(r.lo, r.hi);
  s.ceiling = ceiling;
  if (style == "irregular") {
    // Two wings: rooms merged into L and T shapes beside a diagonal corridor or a pentagonal ring.
    const double w0 = std::max(minimum_region("irregular").x(), rng.uniform(10.0, 15.0) * scale);
    const Region a{{0, 0}, {w0, r.hi.y()}}, c{{w0, 0}, {w0 + r.hi.x(), r.hi.y()}};
    fill("irregular", &s.plan, a, rng, "west_", IrregularVariant::kMergedRooms);
    fill("irregular", &s.plan, c, rng, "east_",
         rng.chance(0.5) ? IrregularVariant::kDiagonal : IrregularVariant::kPentagon);
    s.slab = rect_polygon(a.lo, c.hi);
  } else {
    fill(style, &s.plan, r, rng, "");
  }
  b.storeys.push_back(std::move(s));
  return b;
}

Building mixed(double scale, bool realistic, Rng& rng) {
  static const std::vector<std::string> kWingStyles = {"office", "atrium", "library", "open_plan",
                                                       "irregular"};
  const int n = rng.chance(0.7) ? 2 : 3;
  std::vector<std::string> styles;
  for (int i = 0; i < n; ++i) styles.push_back(rng.pick(kWingStyles));
  if (std::adjacent_find(styles.begin(), styles.end()) != styles.end() && n == 2)
    styles[1] = styles[0] == "office" ? "library" : "office";
  std::vector<Region> wings;
  double x = 0.0;
  for (const std::string& st : styles) {
    // Wings are smaller than whole buildings of their style.
    const StyleSize z = size_of(st, scale * 0.7);
    const double w = rng.uniform(z.w_lo, z.w_hi);
    const double h = rng.uniform(z.h_lo, z.h_hi);
    wings.push_back({{x, 0.0}, {x + w, h}});
    x += w;
  }
  const FloorPlanRules rules = draw_rules(rng);
  Building b;
  const auto atrium = std::find(styles.begin(), styles.end(), "atrium");
  if (atrium != styles.end())
    b.storeys.push_back(
        lobby_below(wings[atrium - styles.begin()], rules, rng.uniform(kCeilingMin, kCeilingMax)));
  Storey s;
  s.name = "L" + std::to_string(b.storeys.size());
  s.plan.rules = rules;
  s.plan.realistic = realistic;
  s.ceiling = rng.uniform(kCeilingMin, kCeilingMax);
  for (std::size_t i = 0; i < wings.size(); ++i)
    fill(styles[i], &s.plan, wings[i], rng, "wing" + std::to_string(i + 1) + "_");
  s.slab = staircase(wings);
  b.storeys.push_back(std::move(s));
  return b;
}

Building multi_storey(double scale, bool realistic, Rng& rng) {
  static const std::vector<std::string> kGround = {"office", "library", "open_plan", "irregular"};
  static const std::vector<std::string> kUpper = {"office", "library", "open_plan", "irregular", "atrium"};
  const int n = rng.chance(0.8) ? 2 : 3;
  const double ceiling = rng.uniform(kCeilingMin, 3.0);
  const double rise = ceiling + kSlabThickness;
  const double run = rise / rng.uniform(kRampSlopeMin, kRampSlopeMax);
  const double wr = rng.uniform(kRampWidthMin, kRampWidthMax), wg = rng.uniform(kGalleryMin, kGalleryMax);
  const double ws = wr + wg;
  const double W = run + rng.uniform(2 * kRampEndMin + 1.0, 2 * kRampEndMin + 4.0);
  const double H =
      std::max(minimum_region("office").y(), rng.uniform(8.0, 13.0) * scale) + ws * (n == 3 ? 2 : 1);
  const FloorPlanRules rules = draw_rules(rng);
  Building b;
  // Ramp k joins storeys k and k + 1: along the south facade for even k, the north for odd.
  struct RampPlace {
    bool south;
    double x0;
  };
  std::vector<RampPlace> places;
  for (int k = 0; k + 1 < n; ++k)
    places.push_back({k % 2 == 0, rng.uniform(kRampEndMin, W - run - kRampEndMin)});
  for (int j = 0; j < n; ++j) {
    Storey s;
    s.name = "L" + std::to_string(j);
    s.plan.rules = rules;
    s.plan.realistic = realistic;
    s.ceiling = ceiling;
    s.slab = rect_polygon({0, 0}, {W, H});
    double y_lo = 0.0, y_hi = H;
    for (int k = 0; k + 1 < n; ++k) {
      if (k != j && k + 1 != j) continue;
      const RampPlace& p = places[k];
      const bool lower = k == j;
      const double s0 = p.south ? 0.0 : H - wr, s1 = p.south ? wr : H;      // the ramp's strip
      const double g0 = p.south ? wr : H - ws, g1 = p.south ? ws : H - wr;  // the gallery beside it
      if (p.south)
        y_lo = ws;
      else
        y_hi = H - ws;
      const std::string side = s.name + "_" + (p.south ? "south_" : "north_");
      const int gallery = s.plan.add_rect(side + "gallery", SpaceKind::kCorridor, {0, g0}, {W, g1});
      const int west =
          s.plan.add_rect(side + (lower ? "landing" : "balcony"), SpaceKind::kCorridor, {0, s0}, {p.x0, s1});
      s.plan.open_joints.push_back({gallery, west});
      if (lower) {
        const int ramp = s.plan.add_rect(side + "ramp", SpaceKind::kRamp, {p.x0, s0}, {p.x0 + run, s1});
        s.plan.open_joints.push_back({west, ramp});
        const int store =
            s.plan.add_rect(side + "store", SpaceKind::kRoom, {p.x0 + run, s0}, {W, s1}, Furnishing::kOffice);
        s.plan.doors.push_back(random_door(store, gallery, rng));
        scene::Ramp r;
        r.from_level = j;
        r.to_level = j + 1;
        r.polygon = rect_polygon({p.x0, s0}, {p.x0 + run, s1});
        r.axis = Vec2::UnitX();
        b.ramps.push_back(r);
      } else {
        const int well = s.plan.add_rect(side + "ramp_well", SpaceKind::kVoid, {p.x0, s0}, {p.x0 + run, s1});
        const int top = s.plan.add_rect(side + "landing", SpaceKind::kCorridor, {p.x0 + run, s0}, {W, s1});
        s.plan.open_joints.push_back({gallery, top});
        s.plan.no_railing.push_back({well, top});
      }
    }
    const std::string st = rng.pick(j == 0 ? kGround : kUpper);
    fill(st, &s.plan, {{0, y_lo}, {W, y_hi}}, rng, s.name + "_");  // names unique over the storeys
    b.storeys.push_back(std::move(s));
  }
  return b;
}

}  // namespace

Polygon2 rect_polygon(const Vec2& lo, const Vec2& hi) { return {lo, {hi.x(), lo.y()}, hi, {lo.x(), hi.y()}}; }

Building draw_building(const std::string& style, double scale, bool realistic, Rng& rng) {
  return style == "mixed"          ? mixed(scale, realistic, rng)
         : style == "multi_storey" ? multi_storey(scale, realistic, rng)
                                   : single_wing(style, scale, realistic, rng);
}

}  // namespace tsgraphs::generator::internal
