#include "tsgraphs/generator/door_leaves.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "tsgraphs/generator/furnishing.hpp"

namespace tsgraphs::generator {
namespace {

constexpr double kSingleLeafMin =
    0.85;                               // m: the narrowest door a 0.3 m clearance passes beside its open leaf
constexpr double kSingleLeafMax = 1.2;  // m: the widest one leaf (wider doors have two)
constexpr double kDoubleDoorChance = 0.1;  // of a door being a double door
constexpr double kDoubleDoorMin = 1.4;     // m: double doors, two leaves of half the width
constexpr double kDoubleDoorMax = 1.8;
constexpr double kLeafThickness = 0.04;  // m: a door leaf
constexpr double kLeafTopGap = 0.02;     // m between the leaf and the door's head
constexpr double kLeafGap = 0.005;       // m between the two leaves of a double door (and each from its jamb)
constexpr double kAngleMinDeg = 30.0;    // a leaf is open this far at least (ajar)...
constexpr double kAngleMaxDeg = 120.0;   // ...and at most (swung back towards its wall)
constexpr int kAngleDraws = 8;           // angles drawn per hinge and side before the next is tried
constexpr double kSweepStepDeg = 10.0;  // the swing is checked at this step: a leaf never went through a wall
constexpr double kProbeBeyondWall = 0.05;  // m past a wall's face where the space on that side is looked up
constexpr double kOnLine = 1e-6;           // m: a face edge this close to the door's wall line is that wall

struct Door {
  Vec2 center, u;  ///< the opening's centre on the wall's centre line, the wall's direction
  double width, height, half_wall;
};

/// A leaf hinged at `hinge`, `angle` open from lying across the opening along `u_in` towards
/// the side `n`: its thickness stays outside the doorway when it stands at 90 degrees.
OrientedRect leaf_at(const Vec2& hinge, const Vec2& u_in, const Vec2& n, double length, double angle) {
  const Vec2 d = std::cos(angle) * u_in + std::sin(angle) * n;
  const Vec2 p = -std::sin(angle) * u_in + std::cos(angle) * n;
  OrientedRect r;
  r.center = hinge + 0.5 * length * d + 0.5 * kLeafThickness * p;
  r.size = Vec2(length, kLeafThickness);
  r.yaw = std::atan2(d.y(), d.x());
  return r;
}

/// One leaf's hinge and swing.
struct Swing {
  Vec2 hinge, u_in;
  double length, angle;
};

bool inside(const Polygon2& face, const OrientedRect& r) {
  for (const Vec2& p : r.corners()) {
    if (!contains(face, p)) return false;
  }
  return true;
}

/// The part of [a, b] with (x - o) x d of sign `side` (or on the line); false when none.
bool clip_to_side(Vec2* a, Vec2* b, const Vec2& o, const Vec2& d, double side) {
  const auto f = [&](const Vec2& x) { return side * (d.x() * (x - o).y() - d.y() * (x - o).x()); };
  const double fa = f(*a), fb = f(*b);
  if (fa < 0.0 && fb < 0.0) return false;
  if (fa < 0.0) *a = *a + (*b - *a) * (fa / (fa - fb));
  if (fb < 0.0) *b = *b + (*a - *b) * (fb / (fb - fa));
  return true;
}

/// Whether a set of leaves (one, or the two of a double door) hangs well on side `n` of
/// `door` in the space of `face`.
class LeafCheck {
 public:
  LeafCheck(const Door& door, const Vec2& n, const Polygon2& face, double passage,
            const std::vector<DoorApproach>& others, const std::vector<OrientedRect>& leaves)
      : door_(door), n_(n), face_(face), passage_(passage), others_(others), leaves_(leaves) {}

  bool ok(const std::vector<Swing>& swings) const {
    std::vector<OrientedRect> rects;
    for (const Swing& s : swings) {
      const OrientedRect r = leaf_at(s.hinge, s.u_in, n_, s.length, s.angle);
      if (!swept_inside(s) || !clear_of_others(r) || !tip_has_room(s, r)) return false;
      rects.push_back(r);
    }
    // The doorway keeps its width, or a passage, between a leaf and the far jamb (or the other leaf).
    const double need = std::min(passage_, door_.width) - 1e-9;
    if (rects.size() == 2) return distance(rects[0], rects[1]) >= need;
    const Vec2 far_jamb = swings[0].hinge + door_.width * swings[0].u_in;
    return distance(rects[0], far_jamb) >= need;
  }

 private:
  /// Inside the face all along its swing from closed: it went through no wall.
  bool swept_inside(const Swing& s) const {
    const double step = kSweepStepDeg * M_PI / 180.0;
    for (double a = 0.0; a < s.angle; a += step) {
      if (!inside(face_, leaf_at(s.hinge, s.u_in, n_, s.length, a))) return false;
    }
    return inside(face_, leaf_at(s.hinge, s.u_in, n_, s.length, s.angle));
  }

  bool clear_of_others(const OrientedRect& r) const {
    for (const DoorApproach& a : others_) {
      if ((a.center - door_.center).norm() > kOnLine && distance(r, a.center) < a.radius) return false;
    }
    for (const OrientedRect& l : leaves_) {
      if (distance(r, l) < passage_) return false;
    }
    return true;
  }

  /// A passage round the leaf's free end to every wall on the doorway's side of it (the pocket
  /// behind it, between the leaf and its own wall, is a dead end and may be narrow).
  bool tip_has_room(const Swing& s, const OrientedRect& r) const {
    const Vec2 d(std::cos(r.yaw), std::sin(r.yaw));
    const Vec2 tip = s.hinge + s.length * d;
    const Vec2 to_door = door_.center - s.hinge;
    const double side = d.x() * to_door.y() - d.y() * to_door.x() >= 0.0 ? 1.0 : -1.0;
    const Vec2 across(-door_.u.y(), door_.u.x());
    for (std::size_t i = 0; i < face_.size(); ++i) {
      Vec2 a = face_[i], b = face_[(i + 1) % face_.size()];
      const bool on_wall = std::abs((a - door_.center).dot(across)) < door_.half_wall + kOnLine &&
                           std::abs((b - door_.center).dot(across)) < door_.half_wall + kOnLine;
      if (on_wall || !clip_to_side(&a, &b, s.hinge, d, side)) continue;
      if (distance_to_segment(tip, a, b) < passage_) return false;
    }
    return true;
  }

  const Door& door_;
  Vec2 n_;
  const Polygon2& face_;
  double passage_;
  const std::vector<DoorApproach>& others_;
  const std::vector<OrientedRect>& leaves_;
};

double random_angle(Rng& rng) { return rng.uniform(kAngleMinDeg, kAngleMaxDeg) * M_PI / 180.0; }

/// The swings of a door's leaves on side `n` that pass `check`, or nothing.
std::optional<std::vector<Swing>> swing_leaves(const Door& door, const Vec2& n, const LeafCheck& check,
                                               Rng& rng) {
  const Vec2 off = (door.half_wall + kLeafThickness) * n;
  const Vec2 left = door.center - 0.5 * door.width * door.u + off,
             right = door.center + 0.5 * door.width * door.u + off;
  if (door.width > kSingleLeafMax + 1e-9) {
    const double length = 0.5 * door.width - kLeafGap;
    for (int k = 0; k < kAngleDraws; ++k) {
      const double a0 = random_angle(rng);
      const double a1 = random_angle(rng);
      const std::vector<Swing> swings = {{left, door.u, length, a0}, {right, -door.u, length, a1}};
      if (check.ok(swings)) return swings;
    }
    return std::nullopt;
  }
  const bool left_first = rng.chance(0.5);
  for (const bool at_left : {left_first, !left_first}) {
    const Swing base = at_left ? Swing{left, door.u, door.width - kLeafGap, 0.0}
                               : Swing{right, -door.u, door.width - kLeafGap, 0.0};
    for (int k = 0; k < kAngleDraws; ++k) {
      Swing s = base;
      s.angle = random_angle(rng);
      if (check.ok({s})) return std::vector<Swing>{s};
    }
  }
  return std::nullopt;
}

/// Rooms first (a door opens into the room), then halls, then corridors.
int swing_rank(SpaceKind k) {
  return k == SpaceKind::kRoom ? 0 : k == SpaceKind::kHall ? 1 : k == SpaceKind::kCorridor ? 2 : 3;
}

scene::Box leaf_box(const OrientedRect& r, double height, int level) {
  scene::Box b;
  b.level = level;
  b.min = Eigen::Vector3d(r.center.x() - 0.5 * r.size.x(), r.center.y() - 0.5 * r.size.y(), 0.0);
  b.max = Eigen::Vector3d(r.center.x() + 0.5 * r.size.x(), r.center.y() + 0.5 * r.size.y(), height);
  b.yaw_deg = r.yaw * 180.0 / M_PI;
  b.label = scene::kDoorLeafLabel;
  return b;
}

}  // namespace

void draw_door_widths(FloorPlan* plan, Rng& rng) {
  for (DoorSpec& d : plan->doors) {
    d.width = rng.chance(kDoubleDoorChance) ? rng.uniform(kDoubleDoorMin, kDoubleDoorMax)
                                            : rng.uniform(kSingleLeafMin, kSingleLeafMax);
  }
}

std::vector<OrientedRect> hang_door_leaves(const FloorPlan& plan, const PlanResult& result, int level,
                                           double passage, Rng& rng, scene::Scene* scene) {
  const std::vector<DoorApproach> approaches = door_approaches(*scene, level);
  std::vector<OrientedRect> leaves;
  for (const PlanWall& pw : result.walls) {
    if (pw.b < 0) continue;
    const scene::Wall& wall = scene->walls[pw.wall];
    const Vec2 u = (wall.to - wall.from).normalized(), n(-u.y(), u.x());
    for (const scene::Opening& o : wall.openings) {
      if (o.sill > 0.0) continue;
      const Door door{wall.from + o.at * u, u, o.width, o.height, 0.5 * wall.thickness};
      const Vec2 probe = door.center + (door.half_wall + kProbeBeyondWall) * n;
      const int plus = contains(plan.spaces[pw.a].outline, probe) ? pw.a : pw.b;
      const int minus = plus == pw.a ? pw.b : pw.a;
      std::vector<std::pair<int, Vec2>> sides = {{plus, n}, {minus, -n}};
      const int r0 = swing_rank(plan.spaces[plus].kind), r1 = swing_rank(plan.spaces[minus].kind);
      if (r1 < r0 || (r1 == r0 && rng.chance(0.5))) std::swap(sides[0], sides[1]);
      for (const auto& [space, side] : sides) {
        if (swing_rank(plan.spaces[space].kind) > 2) continue;
        const LeafCheck check(door, side, result.faces[space], passage, approaches, leaves);
        const std::optional<std::vector<Swing>> swings = swing_leaves(door, side, check, rng);
        if (!swings) continue;
        for (const Swing& s : *swings) {
          leaves.push_back(leaf_at(s.hinge, s.u_in, side, s.length, s.angle));
          scene->boxes.push_back(leaf_box(leaves.back(), door.height - kLeafTopGap, level));
        }
        break;
      }
    }
  }
  return leaves;
}

}  // namespace tsgraphs::generator
