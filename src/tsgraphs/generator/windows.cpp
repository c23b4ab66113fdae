#include "tsgraphs/generator/windows.hpp"

#include <algorithm>
#include <cmath>

namespace tsgraphs::generator {
namespace {

constexpr double kFacadeWindowChance = 0.85;  // of a facade wall having windows (the rest: blind, a store's)
constexpr double kGlazedFrontChance = 0.25;   // of a wall between a room and a corridor or hall being glazed
constexpr double kOpenWindowChance = 0.15;    // of a window standing open (no pane)
constexpr double kGlassMin = 0.5;             // share of rays a pane lets through, as the glass railings'
constexpr double kGlassMax = 0.9;
constexpr double kSillMin = 0.8;  // m: a window's sill (a desk's height and a little more)
constexpr double kSillMax = 1.0;
constexpr double kHeadMin = 2.0;  // m: its head (about a door's)
constexpr double kHeadMax = 2.2;
constexpr double kLintelMin = 0.2;  // m of wall kept above a window's head
constexpr double kWidthMin = 0.8;   // m: one window
constexpr double kWidthMax = 2.4;
constexpr double kPierMin = 0.5;  // m of wall between two windows
constexpr double kPierMax = 1.8;
constexpr double kFrontSillMin = 0.9;  // m: a glazed front's sill (a parapet)
constexpr double kFrontSillMax = 1.1;
constexpr double kFrontPaneMin = 1.0;  // m: the panes of a glazed front...
constexpr double kFrontPaneMax = 2.5;
constexpr double kMullion = 0.1;      // ...and the frames between them
constexpr double kEndMargin = 0.4;    // m of solid wall (beyond half a wall) at each end: the corner
constexpr double kDoorSpacing = 0.3;  // m of wall between a window and a door (floor_plan's spacing)

struct Band {
  double sill, head, transmission;
  bool open_chance;  ///< a window may stand open (facades), or every pane is glass (fronts)
};

/// True when [a, b] keeps kDoorSpacing from every opening of `w`; else `next` gets where to go on.
bool clear_of_openings(const scene::Wall& w, double a, double b, double* next) {
  for (const scene::Opening& o : w.openings) {
    const double lo = o.at - 0.5 * o.width - kDoorSpacing, hi = o.at + 0.5 * o.width + kDoorSpacing;
    if (b > lo && a < hi) {
      *next = hi;
      return false;
    }
  }
  return true;
}

/// Windows along `w` between its end margins: widths and piers drawn from the given ranges.
int glaze(scene::Wall* w, const Band& band, double width_lo, double width_hi, double pier_lo, double pier_hi,
          Rng& rng) {
  const double length = (w->to - w->from).norm();
  const double margin = kEndMargin + 0.5 * w->thickness;
  const double hi = length - margin;
  std::vector<scene::Opening> made;
  double s = margin + rng.uniform(0.0, pier_hi - pier_lo);
  while (s + width_lo <= hi) {
    const double width = std::min(rng.uniform(width_lo, width_hi), hi - s);
    double next = 0.0;
    if (!clear_of_openings(*w, s, s + width, &next)) {
      s = next;
      continue;
    }
    scene::Opening o;
    o.at = s + 0.5 * width;
    o.width = width;
    o.sill = band.sill;
    o.height = band.head - band.sill;
    o.transmission = band.open_chance && rng.chance(kOpenWindowChance) ? 1.0 : band.transmission;
    made.push_back(o);
    s += width + rng.uniform(pier_lo, pier_hi);
  }
  w->openings.insert(w->openings.end(), made.begin(), made.end());
  std::sort(w->openings.begin(), w->openings.end(),
            [](const scene::Opening& x, const scene::Opening& y) { return x.at < y.at; });
  return static_cast<int>(made.size());
}

bool is_front(SpaceKind a, SpaceKind b) {
  const auto open = [](SpaceKind k) { return k == SpaceKind::kCorridor || k == SpaceKind::kHall; };
  return (a == SpaceKind::kRoom && open(b)) || (b == SpaceKind::kRoom && open(a));
}

}  // namespace

int add_windows(const FloorPlan& plan, const PlanResult& result, Rng& rng, scene::Scene* scene) {
  const double glass = rng.uniform(kGlassMin, kGlassMax);
  int made = 0;
  for (const PlanWall& pw : result.walls) {
    scene::Wall& w = scene->walls[pw.wall];
    const SpaceKind a = plan.spaces[pw.a].kind;
    const double top = w.height - kLintelMin;
    if (pw.b < 0) {
      if (!is_walkable(a) || !rng.chance(kFacadeWindowChance)) continue;
      const double sill = rng.uniform(kSillMin, kSillMax);
      const double head = std::min(rng.uniform(kHeadMin, kHeadMax), top);
      made += glaze(&w, {sill, head, glass, true}, kWidthMin, kWidthMax, kPierMin, kPierMax, rng);
    } else if (is_front(a, plan.spaces[pw.b].kind) && rng.chance(kGlazedFrontChance)) {
      const double sill = rng.uniform(kFrontSillMin, kFrontSillMax);
      const double head = std::min(plan.rules.door_height, top);
      made += glaze(&w, {sill, head, glass, false}, kFrontPaneMin, kFrontPaneMax, kMullion, kMullion, rng);
    }
  }
  return made;
}

}  // namespace tsgraphs::generator
