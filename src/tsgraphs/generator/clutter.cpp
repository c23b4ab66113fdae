#include "tsgraphs/generator/clutter.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "tsgraphs/core/rect.hpp"
#include "tsgraphs/generator/furnishing.hpp"
#include "tsgraphs/scene/scene_geometry.hpp"
#include "tsgraphs/scene/walkable_grid.hpp"

namespace tsgraphs::generator {
namespace {

constexpr int kPieceDraws = 3;          // kinds tried at one place of a run before it is left a gap
constexpr double kRunChanceRoom = 0.8;  // of a room's wall getting a run of furniture
constexpr double kRunChanceHall = 0.5;  // of a hall's (its middle has shelves or desks already)
constexpr double kRunChanceCorridor =
    0.3;                                // of a corridor's (cabinets, printers, bins where it is wide enough)
constexpr double kRunEdgeMin = 1.0;     // m: a shorter wall gets no run
constexpr double kWallGap = 0.03;       // m between a piece and the wall behind it (furnishing's)
constexpr double kTouchGap = 0.02;      // m: pieces of a run stand this close, or farther
constexpr double kRunGapChance = 0.35;  // of a gap in a run (the wall shows there)
constexpr double kRunGapMin = 0.3;      // m
constexpr double kRunGapMax = 1.5;
constexpr double kRunStartMax = 1.0;   // m from the wall's end where a run starts, at most
constexpr double kChairChance = 0.7;   // of a desk having its chair
constexpr double kChairGapMin = 0.05;  // m between a desk and its chair
constexpr double kChairGapMax = 0.35;
constexpr double kChairTurnDeg = 25.0;      // a chair stands this far askew at most
constexpr double kFreeAreaPerPiece = 10.0;  // m^2 of floor per free-standing piece, at most
constexpr double kFreeChance = 0.6;         // of each such piece being there
constexpr int kFreeDraws = 12;              // places drawn per free-standing piece before giving up
constexpr double kReachTolerance =
    0.05;                         // m: an obstacle this near a wall line reaches it (stands against it)
constexpr double kBehind = 0.02;  // m into the wall a piece stands against where the wall is looked for

struct Kind {
  const char* label;
  double length_lo, length_hi, depth_lo, depth_hi, height_lo, height_hi;
};
// Against a wall: what hides a wall's foot in offices, stores and halls.
constexpr Kind kWallKinds[] = {
    {"cabinet", 0.8, 1.6, 0.4, 0.6, 0.7, 1.3},   {"shelf", 0.8, 2.0, 0.3, 0.45, 1.6, 2.2},
    {"sideboard", 1.2, 2.0, 0.4, 0.5, 0.7, 0.9}, {"radiator", 0.8, 1.6, 0.1, 0.15, 0.5, 0.7},
    {"printer", 0.5, 0.7, 0.5, 0.7, 0.9, 1.2},   {"bin", 0.3, 0.45, 0.3, 0.45, 0.5, 0.8},
    {"boxes", 0.4, 1.0, 0.3, 0.6, 0.3, 1.2},     {"desk", 1.2, 1.8, 0.6, 0.8, 0.72, 0.76},
};
// Along a corridor's walls: nothing one works at.
constexpr Kind kCorridorKinds[] = {
    {"cabinet", 0.8, 1.2, 0.4, 0.5, 0.9, 1.3}, {"printer", 0.5, 0.7, 0.5, 0.6, 0.9, 1.2},
    {"bin", 0.3, 0.45, 0.3, 0.45, 0.5, 0.8},   {"bench", 1.0, 1.8, 0.35, 0.45, 0.4, 0.5},
    {"plant", 0.4, 0.6, 0.4, 0.6, 0.8, 1.6},
};
// Free-standing.
constexpr Kind kFreeKinds[] = {
    {"chair", 0.45, 0.55, 0.45, 0.55, 0.8, 1.0}, {"table", 0.6, 1.2, 0.6, 0.8, 0.72, 0.76},
    {"bin", 0.3, 0.4, 0.3, 0.4, 0.4, 0.7},       {"boxes", 0.3, 0.7, 0.3, 0.7, 0.3, 0.8},
    {"plant", 0.4, 0.6, 0.4, 0.6, 0.8, 1.6},
};
constexpr Kind kChair = {"chair", 0.45, 0.55, 0.45, 0.55, 0.8, 1.0};
constexpr const char* kDesk = "desk";  // the label of the desks chairs go to (furnishing's and ours)

template <std::size_t N>
const Kind& pick(const Kind (&kinds)[N], Rng& rng) {
  return kinds[rng.integer(0, static_cast<int>(N) - 1)];
}

OrientedRect rect(const Vec2& center, double length, double depth, double yaw) {
  OrientedRect r;
  r.center = center;
  r.size = Vec2(length, depth);
  r.yaw = yaw;
  return r;
}

/// What stands on the level below a walker's head, and the doors' approaches: where clutter
/// may go, and where it has gone.
class Floor {
 public:
  Floor(const scene::Scene& scene, int level, std::vector<SharedStretch> joints, double passage)
      : approaches_(door_approaches(scene, level)), joints_(std::move(joints)), passage_(passage) {
    const double headroom = scene::WalkableRules{}.headroom;
    for (const scene::Wall& w : scene.walls) {
      if (w.level != level) continue;
      const Vec2 u = (w.to - w.from).normalized();
      const double yaw = std::atan2(u.y(), u.x());
      std::vector<scene::WallPiece> pieces = scene::wall_pieces(w);
      for (const scene::GlassPane& g : scene::glass_panes(w)) pieces.push_back({g.s0, g.s1, g.z0, g.z1});
      for (const scene::WallPiece& p : pieces) {
        if (p.z0 >= headroom) continue;
        obstacles_.push_back(rect(w.from + 0.5 * (p.s0 + p.s1) * u, p.s1 - p.s0, w.thickness, yaw));
        if (p.z1 >= headroom) walls_.push_back(obstacles_.back());  // what a piece may stand against
      }
    }
    for (const scene::Railing& r : scene.railings) {
      if (r.level != level) continue;
      const Vec2 d = r.to - r.from;
      obstacles_.push_back(rect(0.5 * (r.from + r.to), d.norm(), scene::RailingGeometry::kSolidThickness,
                                std::atan2(d.y(), d.x())));
    }
    for (std::size_t k = 0; k < scene.boxes.size(); ++k) {
      const scene::Box& b = scene.boxes[k];
      if (b.level != level || b.min.z() >= headroom) continue;
      add(rect(0.5 * (b.min.head<2>() + b.max.head<2>()), b.max.x() - b.min.x(), b.max.y() - b.min.y(),
               b.yaw_deg * M_PI / 180.0),
          static_cast<int>(k));
    }
  }

  /// `r` inside `face`, off the doors' approaches and at least `gap` from every obstacle but
  /// `except` (an index into obstacles(), or -1).
  bool fits(const OrientedRect& r, const Polygon2& face, double gap, int except = -1) const {
    for (const Vec2& p : r.corners()) {
      if (!contains(face, p)) return false;
    }
    for (const DoorApproach& d : approaches_) {
      if (distance(r, d.center) < d.radius) return false;
    }
    for (const SharedStretch& j : joints_) {  // an open joint is a doorway without a door
      if (distance(r, j.a, j.b) < passage_) return false;
    }
    for (std::size_t i = 0; i < obstacles_.size(); ++i) {
      if (static_cast<int>(i) != except && distance(r, obstacles_[i]) < gap) return false;
    }
    return true;
  }
  /// For a piece `r` standing against the wall line through `at` (inward: `inward`): true
  /// when every obstacle is either touching it (a run), reaching that wall line too (the gap
  /// between them is a niche against the wall, a dead end), or a passage away.
  bool leaves_passages(const OrientedRect& r, const Vec2& at, const Vec2& inward) const {
    for (const OrientedRect& o : obstacles_) {
      const double d = distance(r, o);
      if (d <= kTouchGap + 1e-9 || d >= passage_) continue;
      double reach = std::numeric_limits<double>::infinity();
      for (const Vec2& c : o.corners()) reach = std::min(reach, (c - at).dot(inward));
      if (reach > kWallGap + kReachTolerance) return false;
    }
    return true;
  }
  /// True when a wall stands at `p` (not an open joint, a door, a window's sill or a railing).
  bool wall_at(const Vec2& p) const {
    for (const OrientedRect& w : walls_) {
      if (w.contains(p)) return true;
    }
    return false;
  }
  /// `zone` inside `face` and meeting no obstacle: a walker's way.
  bool free(const OrientedRect& zone, const Polygon2& face) const {
    for (const Vec2& p : zone.corners()) {
      if (!contains(face, p)) return false;
    }
    for (const OrientedRect& o : obstacles_) {
      if (distance(zone, o) <= 0.0) return false;
    }
    return true;
  }
  /// A new obstacle: the footprint of scene box `box`.
  void add(const OrientedRect& r, int box) {
    obstacles_.push_back(r);
    obstacle_of_box_[box] = static_cast<int>(obstacles_.size()) - 1;
  }
  const std::vector<OrientedRect>& obstacles() const { return obstacles_; }
  /// The obstacle of scene box `box`, -1 when it is none (another level, above the head).
  int obstacle_of_box(int box) const {
    const auto it = obstacle_of_box_.find(box);
    return it == obstacle_of_box_.end() ? -1 : it->second;
  }

 private:
  std::vector<DoorApproach> approaches_;
  std::vector<SharedStretch> joints_;  ///< open joints between walkable spaces, kept a passage clear
  double passage_;
  std::vector<OrientedRect> obstacles_;
  std::vector<OrientedRect> walls_;  ///< wall pieces from the floor to above the head
  std::map<int, int> obstacle_of_box_;
};

scene::Box box_of(const OrientedRect& r, double height, int level, const char* label) {
  scene::Box b;
  b.level = level;
  b.min = Eigen::Vector3d(r.center.x() - 0.5 * r.size.x(), r.center.y() - 0.5 * r.size.y(), 0.0);
  b.max = Eigen::Vector3d(r.center.x() + 0.5 * r.size.x(), r.center.y() + 0.5 * r.size.y(), height);
  b.yaw_deg = r.yaw * 180.0 / M_PI;
  b.label = label;
  return b;
}

/// Places the pieces of one space; each new piece becomes an obstacle of the next.
class Clutterer {
 public:
  Clutterer(Floor* floor, const Polygon2& face, int level, double passage, Rng& rng, scene::Scene* scene)
      : floor_(*floor), face_(face), level_(level), passage_(passage), rng_(rng), scene_(*scene) {}

  /// A run of pieces along face edge i, each with a passage free in front of it.
  void wall_run(std::size_t i, bool corridor) {
    const double orient = signed_area(face_) >= 0 ? 1.0 : -1.0;
    const Vec2 a = face_[i], b = face_[(i + 1) % face_.size()];
    const double length = (b - a).norm();
    const Vec2 u = (b - a) / length, inward = orient * Vec2(-u.y(), u.x());
    const double yaw = std::atan2(u.y(), u.x());
    for (double s = kWallGap + rng_.uniform(0.0, kRunStartMax); s < length - kWallGap;) {
      double l = 0.0;  // of the piece placed here, 0 when none fits
      for (int draw = 0; draw < kPieceDraws && l == 0.0; ++draw) {
        const Kind& k = corridor ? pick(kCorridorKinds, rng_) : pick(kWallKinds, rng_);
        const double lk = rng_.uniform(k.length_lo, k.length_hi), d = rng_.uniform(k.depth_lo, k.depth_hi);
        const double h = rng_.uniform(k.height_lo, k.height_hi);
        if (s + lk > length - kWallGap) continue;
        const OrientedRect r = rect(a + (s + 0.5 * lk) * u + (kWallGap + 0.5 * d) * inward, lk, d, yaw);
        if (fits_against_wall(r, a + s * u, u, lk, d, inward)) {
          place(r, h, k.label);
          l = lk;
        }
      }
      s += (l > 0.0 ? l : kRunGapMin) +
           (rng_.chance(kRunGapChance) ? rng_.uniform(kRunGapMin, kRunGapMax) : kTouchGap);
    }
  }

  /// A chair at the desk obstacles()[desk], on whichever long side has a passage round it.
  void chair_at(int desk) {
    const OrientedRect d = floor_.obstacles()[desk];
    const Vec2 x(std::cos(d.yaw), std::sin(d.yaw)), y(-x.y(), x.x());
    const double side = rng_.uniform(kChair.length_lo, kChair.length_hi);
    const double gap = rng_.uniform(kChairGapMin, kChairGapMax);
    const double turn = rng_.uniform(-kChairTurnDeg, kChairTurnDeg) * M_PI / 180.0;
    const double h = rng_.uniform(kChair.height_lo, kChair.height_hi);
    const double along = rng_.uniform(-0.25, 0.25) * d.size.x();
    for (const double sign : {1.0, -1.0}) {
      const OrientedRect r = rect(d.center + along * x + sign * (0.5 * d.size.y() + gap + 0.5 * side) * y,
                                  side, side, d.yaw + turn);
      if (floor_.fits(r, face_, passage_, desk)) {
        place(r, h, kChair.label);
        return;
      }
    }
  }

  /// A free-standing piece somewhere in the face with a passage all round it.
  void free_piece() {
    Vec2 lo = face_.front(), hi = lo;
    for (const Vec2& p : face_) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    const Kind& k = pick(kFreeKinds, rng_);
    const double l = rng_.uniform(k.length_lo, k.length_hi), d = rng_.uniform(k.depth_lo, k.depth_hi);
    const double h = rng_.uniform(k.height_lo, k.height_hi);
    for (int draw = 0; draw < kFreeDraws; ++draw) {
      const double x = rng_.uniform(lo.x(), hi.x());
      const double y = rng_.uniform(lo.y(), hi.y());
      const double yaw = rng_.uniform(0.0, M_PI);
      const OrientedRect r = rect({x, y}, l, d, yaw);
      if (floor_.fits(r, face_, passage_)) {
        place(r, h, k.label);
        return;
      }
    }
  }

  int placed() const { return placed_; }

 private:
  /// `r` (l long, d deep) standing against the wall from `start` along `u`: a wall behind it
  /// all along, clear of everything, a passage free in front of it and none narrowed round it.
  bool fits_against_wall(const OrientedRect& r, const Vec2& start, const Vec2& u, double l, double d,
                         const Vec2& inward) const {
    for (const double t : {0.0, 0.5, 1.0}) {
      if (!floor_.wall_at(start + t * l * u - kBehind * inward)) return false;
    }
    const Vec2 mid = start + 0.5 * l * u;
    const OrientedRect front = rect(mid + (kWallGap + d + 0.5 * passage_) * inward, l, passage_, r.yaw);
    return floor_.fits(r, face_, kTouchGap) && floor_.free(front, face_) &&
           floor_.leaves_passages(r, start, inward);
  }

  void place(const OrientedRect& r, double height, const char* label) {
    scene_.boxes.push_back(box_of(r, height, level_, label));
    floor_.add(r, static_cast<int>(scene_.boxes.size()) - 1);
    ++placed_;
  }

  Floor& floor_;
  const Polygon2& face_;
  int level_;
  double passage_;
  Rng& rng_;
  scene::Scene& scene_;
  int placed_ = 0;
};

}  // namespace

int add_clutter(const FloorPlan& plan, const PlanResult& result, int level, double passage, Rng& rng,
                scene::Scene* scene) {
  std::vector<SharedStretch> joints;
  for (const auto& [a, b] : plan.open_joints) {
    if (!is_walkable(plan.spaces[a].kind) || !is_walkable(plan.spaces[b].kind)) continue;
    for (const SharedStretch& j : shared_boundary(plan, a, b)) joints.push_back(j);
  }
  Floor floor(*scene, level, joints, passage);
  int placed = 0;
  for (std::size_t s = 0; s < plan.spaces.size(); ++s) {
    const SpaceKind kind = plan.spaces[s].kind;
    if (kind != SpaceKind::kRoom && kind != SpaceKind::kHall && kind != SpaceKind::kCorridor) continue;
    const Polygon2& face = result.faces[s];
    Clutterer c(&floor, face, level, passage, rng, scene);
    const double run_chance = kind == SpaceKind::kRoom   ? kRunChanceRoom
                              : kind == SpaceKind::kHall ? kRunChanceHall
                                                         : kRunChanceCorridor;
    for (std::size_t i = 0; i < face.size(); ++i) {
      if ((face[(i + 1) % face.size()] - face[i]).norm() < kRunEdgeMin) continue;
      if (rng.chance(run_chance)) c.wall_run(i, kind == SpaceKind::kCorridor);
    }
    // Chairs at the desks standing in this space (its own, and those furnish put there).
    const std::size_t boxes = scene->boxes.size();  // not the chairs added here
    for (std::size_t k = 0; k < boxes; ++k) {
      const scene::Box& b = scene->boxes[k];
      if (b.level != level || b.label != kDesk) continue;
      const int desk = floor.obstacle_of_box(static_cast<int>(k));
      if (desk >= 0 && contains(face, 0.5 * (b.min.head<2>() + b.max.head<2>())) && rng.chance(kChairChance))
        c.chair_at(desk);
    }
    const int pieces = static_cast<int>(area(face) / kFreeAreaPerPiece);
    for (int k = 0; k < pieces; ++k) {
      if (rng.chance(kFreeChance)) c.free_piece();
    }
    placed += c.placed();
  }
  return placed;
}

}  // namespace tsgraphs::generator
