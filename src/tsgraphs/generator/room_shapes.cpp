#include "tsgraphs/generator/room_shapes.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

namespace tsgraphs::generator {
namespace {

constexpr double kShapeChance = 0.4;  // of a room or hall losing a piece (most real rooms are rectangles)
constexpr double kCornerNotchShare = 0.45;  // of the cuts: a notch at a corner (an L-shaped room)
constexpr double kChamferShare = 0.3;       // a chamfered corner; the rest: a notch in the middle of a wall
constexpr double kNotchMin = 0.6;           // m: a notch's shortest side (a riser one sees as a corner)
constexpr double kNotchMax = 2.5;           // m: its longest (a closet)
constexpr double kNotchShare =
    0.4;  // of a wall's length a corner notch takes at most (the room stays a room)
constexpr double kChamferMin = 0.8;  // m: the legs of a chamfer, as a diagonal wall across a corner
constexpr double kChamferMax = 1.8;
constexpr double kPierWidthMin = 0.5;  // m: a pilaster or riser standing out of a wall
constexpr double kPierWidthMax = 1.5;
constexpr double kPierDepthMin = 0.3;  // m it stands out
constexpr double kPierDepthMax = 0.8;
constexpr double kShapedAreaMin = 6.0;  // m^2 a reshaped room keeps (the smallest office)
constexpr double kPieceShareMax = 0.2;  // of a room's area its piece takes at most
constexpr double kProbe = 0.05;         // m beyond a wall where its other side is looked up
constexpr double kRightAngle = 1e-6;    // |cos| of a corner taken as a right angle

Vec2 outward(const Vec2& p, const Vec2& q) {
  const Vec2 d = (q - p).normalized();
  return {d.y(), -d.x()};  // outlines are counter-clockwise
}

/// True when the stretch [p, q] of space `self`'s outline has the outside or a room beyond
/// it: a piece cut there takes nothing from a corridor or hall the room opens onto.
bool backs_onto_room_or_facade(const FloorPlan& plan, int self, const Vec2& p, const Vec2& q) {
  const Vec2 out = kProbe * outward(p, q);
  for (const double t : {0.1, 0.5, 0.9}) {
    const Vec2 x = p + t * (q - p) + out;
    for (std::size_t k = 0; k < plan.spaces.size(); ++k) {
      if (static_cast<int>(k) == self || !contains(plan.spaces[k].outline, x)) continue;
      if (plan.spaces[k].kind != SpaceKind::kRoom) return false;
    }
  }
  return true;
}

/// A cut: the room's new outline and the shaft's.
struct Cut {
  Polygon2 room, shaft;
};

/// Right-angled convex corners of `poly` (counter-clockwise).
std::vector<std::size_t> right_corners(const Polygon2& poly) {
  std::vector<std::size_t> out;
  const std::size_t n = poly.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 a = poly[(i + n - 1) % n] - poly[i], b = poly[(i + 1) % n] - poly[i];
    const double cross = -a.x() * b.y() + a.y() * b.x();  // (poly[i] - prev) x (next - poly[i])
    if (cross > 0.0 && std::abs(a.normalized().dot(b.normalized())) < kRightAngle) out.push_back(i);
  }
  return out;
}

/// A notch (or, with `chamfer`, a diagonal cut) at corner i; nothing when the walls there are
/// too short or face a corridor.
std::optional<Cut> corner_cut(const FloorPlan& plan, int self, std::size_t i, bool chamfer, Rng& rng) {
  const Polygon2& poly = plan.spaces[self].outline;
  const std::size_t n = poly.size();
  const Vec2 v = poly[i], prev = poly[(i + n - 1) % n], next = poly[(i + 1) % n];
  const double la = (prev - v).norm(), lb = (next - v).norm();
  const Vec2 a = (prev - v) / la, b = (next - v) / lb;
  double sa, sb;
  if (chamfer) {
    const double hi = std::min({kChamferMax, kNotchShare * la, kNotchShare * lb});
    if (hi < kChamferMin) return std::nullopt;
    sa = sb = rng.uniform(kChamferMin, hi);
  } else {
    const double ha = std::min(kNotchMax, kNotchShare * la), hb = std::min(kNotchMax, kNotchShare * lb);
    if (ha < kNotchMin || hb < kNotchMin) return std::nullopt;
    sa = rng.uniform(kNotchMin, ha);
    sb = rng.uniform(kNotchMin, hb);
  }
  if (!backs_onto_room_or_facade(plan, self, v + sa * a, v) ||
      !backs_onto_room_or_facade(plan, self, v, v + sb * b))
    return std::nullopt;
  Cut cut;
  for (std::size_t k = 0; k < n; ++k) {
    if (k != i) {
      cut.room.push_back(poly[k]);
    } else if (chamfer) {
      cut.room.insert(cut.room.end(), {v + sa * a, v + sb * b});
    } else {
      cut.room.insert(cut.room.end(), {v + sa * a, v + sa * a + sb * b, v + sb * b});
    }
  }
  cut.shaft = chamfer ? Polygon2{v, v + sb * b, v + sa * a}
                      : Polygon2{v, v + sb * b, v + sa * a + sb * b, v + sa * a};
  return cut;
}

/// A pilaster or riser standing out of the middle of wall i (poly[i] to poly[i + 1]).
std::optional<Cut> wall_notch(const FloorPlan& plan, int self, std::size_t i, Rng& rng) {
  const Polygon2& poly = plan.spaces[self].outline;
  const Vec2 p = poly[i], q = poly[(i + 1) % poly.size()];
  const double length = (q - p).norm();
  const double width = rng.uniform(kPierWidthMin, kPierWidthMax),
               depth = rng.uniform(kPierDepthMin, kPierDepthMax);
  if (length < 2.0 * kNotchMin + width) return std::nullopt;
  const Vec2 u = (q - p) / length, in(-u.y(), u.x());
  const double s = rng.uniform(kNotchMin, length - kNotchMin - width);
  const Vec2 p1 = p + s * u, p4 = p1 + width * u;
  if (!backs_onto_room_or_facade(plan, self, p1, p4)) return std::nullopt;
  Cut cut;
  for (std::size_t k = 0; k < poly.size(); ++k) {
    cut.room.push_back(poly[k]);
    if (k == i) cut.room.insert(cut.room.end(), {p1, p1 + depth * in, p4 + depth * in, p4});
  }
  cut.shaft = {p1, p4, p4 + depth * in, p1 + depth * in};
  return cut;
}

}  // namespace

int shape_rooms(FloorPlan* plan, Rng& rng) {
  int shaped = 0;
  const std::size_t n = plan->spaces.size();  // shafts added below are not cut again
  for (std::size_t s = 0; s < n; ++s) {
    const SpaceKind kind = plan->spaces[s].kind;
    if ((kind != SpaceKind::kRoom && kind != SpaceKind::kHall) || !rng.chance(kShapeChance)) continue;
    const Polygon2& poly = plan->spaces[s].outline;
    const double u = rng.unit();
    std::optional<Cut> cut;
    if (u < kCornerNotchShare + kChamferShare) {
      const std::vector<std::size_t> corners = right_corners(poly);
      if (corners.empty()) continue;
      const std::size_t i = corners[rng.integer(0, static_cast<int>(corners.size()) - 1)];
      cut = corner_cut(*plan, static_cast<int>(s), i, u >= kCornerNotchShare, rng);
    } else {
      cut = wall_notch(*plan, static_cast<int>(s),
                       static_cast<std::size_t>(rng.integer(0, static_cast<int>(poly.size()) - 1)), rng);
    }
    if (!cut || find_self_intersection(cut->room)) continue;
    const double before = area(poly), piece = area(cut->shaft);
    if (before - piece < kShapedAreaMin || piece > kPieceShareMax * before) continue;
    const std::string name = plan->spaces[s].name + "_shaft";
    plan->spaces[s].outline = cut->room;
    plan->add(name, SpaceKind::kShaft, cut->shaft);
    ++shaped;
  }
  return shaped;
}

}  // namespace tsgraphs::generator
