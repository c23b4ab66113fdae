#include "tsgraphs/generator/floor_plan.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <optional>
#include <tuple>
#include <stdexcept>

namespace tsgraphs::generator {
namespace {

constexpr double kEps = 1e-6;            // m: points this close are one point
constexpr double kKeyScale = 1e5;        // segment ends are matched on a 10 micrometre grid
constexpr double kDoorMinSpacing = 0.3;  // m of wall between two doors of one wall

enum class EdgeKind { kWall, kFacade, kRailing, kOpen };

/// A piece of boundary between at most two spaces (b = -1: the outside).
struct Elementary {
  Vec2 p, q;
  int a = -1, b = -1;
  EdgeKind kind = EdgeKind::kWall;
};

std::pair<long long, long long> key_of(const Vec2& p) {
  return {std::llround(p.x() * kKeyScale), std::llround(p.y() * kKeyScale)};
}

bool in_pairs(const std::vector<std::pair<int, int>>& pairs, int a, int b) {
  for (const auto& [x, y] : pairs) {
    if ((x == a && y == b) || (x == b && y == a)) return true;
  }
  return false;
}

/// Every space's outline cut at every other vertex lying on it, matched into pieces shared by
/// two spaces or facing the outside.
class Subdivision {
 public:
  explicit Subdivision(const FloorPlan& plan) : plan_(plan) {
    std::vector<Vec2> vertices;
    for (const Space& s : plan.spaces) vertices.insert(vertices.end(), s.outline.begin(), s.outline.end());
    using Key = std::pair<std::pair<long long, long long>, std::pair<long long, long long>>;
    std::map<Key, std::size_t> index;
    for (std::size_t si = 0; si < plan.spaces.size(); ++si) {
      const Polygon2& o = plan.spaces[si].outline;
      for (std::size_t e = 0; e < o.size(); ++e) {
        const Vec2 p = o[e], q = o[(e + 1) % o.size()];
        const double len = (q - p).norm();
        std::vector<double> cuts = {0.0, 1.0};
        for (const Vec2& v : vertices) {
          const double t = (v - p).dot(q - p) / (len * len);
          if (t > kEps / len && t < 1.0 - kEps / len && distance_to_segment(v, p, q) < kEps)
            cuts.push_back(t);
        }
        std::sort(cuts.begin(), cuts.end());
        for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
          if ((cuts[k + 1] - cuts[k]) * len < kEps) continue;
          const Vec2 a = p + cuts[k] * (q - p), b = p + cuts[k + 1] * (q - p);
          auto ka = key_of(a), kb = key_of(b);
          const Key key = ka < kb ? Key{ka, kb} : Key{kb, ka};
          const auto it = index.find(key);
          if (it == index.end()) {
            index[key] = pieces_.size();
            pieces_.push_back({a, b, static_cast<int>(si), -1, EdgeKind::kWall});
            edge_of_.push_back({{static_cast<int>(si), static_cast<int>(e)}});
          } else {
            Elementary& piece = pieces_[it->second];
            // Neighbours run along a shared piece in opposite directions; the same direction means
            // the two spaces lie on the same side of it: they overlap.
            const bool same_direction = (piece.p - a).norm() < kEps;
            if (piece.b >= 0 || piece.a == static_cast<int>(si) || same_direction)
              throw std::invalid_argument("floor plan: spaces '" + plan.spaces[piece.a].name + "' and '" +
                                          plan.spaces[si].name + "' overlap");
            piece.b = static_cast<int>(si);
            edge_of_[it->second].push_back({static_cast<int>(si), static_cast<int>(e)});
          }
        }
      }
    }
    for (Elementary& piece : pieces_) piece.kind = classify(piece);
  }

  const std::vector<Elementary>& pieces() const { return pieces_; }
  /// (space, edge index) of the outlines a piece came from.
  const std::vector<std::pair<int, int>>& edges_of(std::size_t piece) const { return edge_of_[piece]; }

  /// Straight maximal stretches of pieces between spaces a and b (b = -1: the outside).
  std::vector<SharedStretch> stretches(int a, int b) const {
    std::vector<const Elementary*> mine;
    for (const Elementary& piece : pieces_) {
      if ((piece.a == a && piece.b == b) || (piece.a == b && piece.b == a)) mine.push_back(&piece);
    }
    return merge(mine);
  }

  /// Maximal straight stretches of pieces of one kind between one pair of spaces, with the pair.
  struct Run {
    SharedStretch s;
    int a, b;
    EdgeKind kind;
  };
  std::vector<Run> runs() const {
    std::map<std::tuple<int, int, int>, std::vector<const Elementary*>> groups;
    for (const Elementary& piece : pieces_) {
      if (piece.kind == EdgeKind::kOpen) continue;
      groups[{std::min(piece.a, piece.b), std::max(piece.a, piece.b), static_cast<int>(piece.kind)}]
          .push_back(&piece);
    }
    std::vector<Run> out;
    for (const auto& [key, pieces] : groups) {
      for (const SharedStretch& s : merge(pieces))
        out.push_back({s, std::get<0>(key), std::get<1>(key), static_cast<EdgeKind>(std::get<2>(key))});
    }
    return out;
  }

 private:
  EdgeKind classify(const Elementary& piece) const {
    if (piece.b < 0) return EdgeKind::kFacade;
    const SpaceKind ka = plan_.spaces[piece.a].kind, kb = plan_.spaces[piece.b].kind;
    if (in_pairs(plan_.open_joints, piece.a, piece.b)) return EdgeKind::kOpen;
    const bool void_a = ka == SpaceKind::kVoid, void_b = kb == SpaceKind::kVoid;
    if (void_a && void_b) return EdgeKind::kOpen;
    if (void_a || void_b)
      return in_pairs(plan_.no_railing, piece.a, piece.b) ? EdgeKind::kOpen : EdgeKind::kRailing;
    return EdgeKind::kWall;
  }

  /// Joins collinear pieces that touch end to end into stretches (longest first).
  static std::vector<SharedStretch> merge(std::vector<const Elementary*> pieces) {
    std::vector<SharedStretch> out;
    std::vector<bool> used(pieces.size(), false);
    for (std::size_t i = 0; i < pieces.size(); ++i) {
      if (used[i]) continue;
      used[i] = true;
      Vec2 a = pieces[i]->p, b = pieces[i]->q;
      const Vec2 dir = (b - a).normalized();
      for (bool grew = true; grew;) {
        grew = false;
        for (std::size_t j = 0; j < pieces.size(); ++j) {
          if (used[j]) continue;
          const Vec2 p = pieces[j]->p, q = pieces[j]->q;
          const Vec2 d = (q - p).normalized();
          if (std::abs(d.x() * dir.y() - d.y() * dir.x()) > 1e-9) continue;
          for (const auto& [u, v] : {std::pair{p, q}, std::pair{q, p}}) {
            if ((u - b).norm() < kEps && (v - b).dot(dir) > 0) {
              b = v;
              used[j] = grew = true;
              break;
            }
            if ((u - a).norm() < kEps && (a - v).dot(dir) > 0) {
              a = v;
              used[j] = grew = true;
              break;
            }
          }
        }
      }
      out.push_back({a, b});
    }
    std::stable_sort(out.begin(), out.end(), [](const SharedStretch& x, const SharedStretch& y) {
      return (x.b - x.a).norm() > (y.b - y.a).norm();
    });
    return out;
  }

  const FloorPlan& plan_;
  std::vector<Elementary> pieces_;
  std::vector<std::vector<std::pair<int, int>>> edge_of_;
};

double thickness_of(EdgeKind kind, const FloorPlanRules& rules) {
  switch (kind) {
    case EdgeKind::kWall:
      return rules.interior_wall;
    case EdgeKind::kFacade:
      return rules.exterior_wall;
    case EdgeKind::kRailing:
      return scene::RailingGeometry::kSolidThickness;
    case EdgeKind::kOpen:
      break;
  }
  return 0.0;
}

/// The usable length of a stretch for a door: its length less the jambs and half a wall at each end.
double door_room(const SharedStretch& s, const FloorPlanRules& rules) {
  return (s.b - s.a).norm() - 2.0 * (rules.jamb + 0.5 * rules.interior_wall);
}

int priority(SpaceKind a, SpaceKind b) {
  const auto circulation = [](SpaceKind k) { return k == SpaceKind::kCorridor || k == SpaceKind::kHall; };
  if (circulation(a) && circulation(b)) return 0;
  if (circulation(a) || circulation(b)) return 1;
  return 2;
}

}  // namespace

int FloorPlan::add(const std::string& name, SpaceKind kind, const Polygon2& outline, Furnishing f) {
  Polygon2 o = outline;
  if (signed_area(o) < 0) std::reverse(o.begin(), o.end());
  spaces.push_back({name, kind, o, f});
  return static_cast<int>(spaces.size()) - 1;
}

int FloorPlan::add_rect(const std::string& name, SpaceKind kind, const Vec2& lo, const Vec2& hi,
                        Furnishing f) {
  return add(name, kind, {lo, {hi.x(), lo.y()}, hi, {lo.x(), hi.y()}}, f);
}

bool is_ground_truth(SpaceKind kind) {
  return kind == SpaceKind::kRoom || kind == SpaceKind::kCorridor || kind == SpaceKind::kHall;
}

bool is_walkable(SpaceKind kind) { return kind != SpaceKind::kVoid && kind != SpaceKind::kShaft; }

std::vector<SharedStretch> shared_boundary(const FloorPlan& plan, int a, int b) {
  return Subdivision(plan).stretches(a, b);
}

void connect_spaces(FloorPlan* plan, Rng& rng) {
  const std::size_t n = plan->spaces.size();
  std::vector<int> group(n);
  std::iota(group.begin(), group.end(), 0);
  const auto find = [&](int x) {
    while (group[x] != x) x = group[x] = group[group[x]];
    return x;
  };
  const auto join = [&](int a, int b) { group[find(a)] = find(b); };
  const Subdivision sub(*plan);
  // A door wanted between spaces that share no stretch wide enough (a room of a block that
  // does not reach the corridor) is not made; the repair below joins that room instead.
  const auto fits = [&](int a, int b) {
    for (const SharedStretch& s : sub.stretches(a, b)) {
      if (door_room(s, plan->rules) >= plan->rules.min_door) return true;
    }
    return false;
  };
  plan->doors.erase(std::remove_if(plan->doors.begin(), plan->doors.end(),
                                   [&](const DoorSpec& d) { return d.a == d.b || !fits(d.a, d.b); }),
                    plan->doors.end());
  for (const DoorSpec& d : plan->doors) join(d.a, d.b);
  for (const auto& [a, b] : plan->open_joints) join(a, b);
  for (;;) {
    std::vector<int> roots;
    for (std::size_t i = 0; i < n; ++i) {
      if (is_walkable(plan->spaces[i].kind) &&
          std::find(roots.begin(), roots.end(), find(static_cast<int>(i))) == roots.end())
        roots.push_back(find(static_cast<int>(i)));
    }
    if (roots.size() <= 1) return;
    // The best door between two groups: circulation first, then the longest stretch.
    int best_a = -1, best_b = -1, best_rank = 3;
    double best_len = 0.0;
    for (const Elementary& piece : sub.pieces()) {
      if (piece.b < 0 || piece.kind != EdgeKind::kWall) continue;
      const SpaceKind ka = plan->spaces[piece.a].kind, kb = plan->spaces[piece.b].kind;
      if (!is_walkable(ka) || !is_walkable(kb) || ka == SpaceKind::kRamp || kb == SpaceKind::kRamp) continue;
      if (find(piece.a) == find(piece.b)) continue;
      double len = 0.0;
      for (const SharedStretch& s : sub.stretches(piece.a, piece.b))
        len = std::max(len, door_room(s, plan->rules));
      if (len < plan->rules.min_door) continue;
      const int rank = priority(ka, kb);
      if (rank < best_rank || (rank == best_rank && len > best_len + kEps)) {
        best_rank = rank;
        best_len = len;
        best_a = piece.a;
        best_b = piece.b;
      }
    }
    if (best_a < 0) throw std::invalid_argument("floor plan: some spaces cannot be joined by a door");
    plan->doors.push_back({best_a, best_b, std::min(best_len, rng.uniform(0.9, 1.4)), rng.uniform(0.2, 0.8)});
    join(best_a, best_b);
  }
}

namespace {

/// A wall of the plan before its doors: the spaces on either side (b = -1: the outside).
struct PendingWall {
  scene::Wall wall;
  int a, b;
};

/// The plan's walls and railings: one per straight stretch between one pair of spaces. The
/// railings go into `scene`; the walls are returned, to take their doors first.
std::vector<PendingWall> walls_and_railings(const Subdivision& sub, const FloorPlanRules& rules, int level,
                                            double ceiling, scene::Scene* scene) {
  std::vector<PendingWall> walls;
  for (const auto& run : sub.runs()) {
    if (run.kind == EdgeKind::kRailing) {
      scene::Railing r;
      r.level = level;
      r.from = run.s.a;
      r.to = run.s.b;
      r.height = rules.railing_height;
      r.style = rules.railing;
      r.transmission = rules.glass_transmission;
      scene->railings.push_back(r);
      continue;
    }
    scene::Wall w;
    w.level = level;
    w.from = run.s.a;
    w.to = run.s.b;
    w.thickness = thickness_of(run.kind, rules);
    w.height = ceiling;
    walls.push_back({w, run.a, run.b});
  }
  return walls;
}

/// The longest stretch of the door's pair's wall, and in `room` the door's room on it (0 when none).
PendingWall* door_host(std::vector<PendingWall>& walls, const DoorSpec& d, const FloorPlanRules& rules,
                       double* room) {
  PendingWall* host = nullptr;
  *room = 0.0;
  for (PendingWall& pw : walls) {
    if (!((pw.a == d.a && pw.b == d.b) || (pw.a == d.b && pw.b == d.a))) continue;
    const double r = door_room({pw.wall.from, pw.wall.to}, rules);
    if (r > *room) {
      *room = r;
      host = &pw;
    }
  }
  return host;
}

/// Where a door of `width` fits among the wall's other doors: the wanted place (`position` of
/// the free length), else the nearest free one; none when the wall is full.
std::optional<double> door_place(const scene::Wall& w, double width, double position,
                                 const FloorPlanRules& rules) {
  const double length = (w.to - w.from).norm();
  const double margin = rules.jamb + 0.5 * rules.interior_wall;
  const double lo = margin + 0.5 * width, hi = length - margin - 0.5 * width;
  const double wanted = lo + std::clamp(position, 0.0, 1.0) * (hi - lo);
  std::optional<double> at;
  for (int k = 0; k <= 40 && !at; ++k) {
    for (double sign : {1.0, -1.0}) {
      const double c = wanted + sign * k * (hi - lo) / 40.0;
      if (c < lo - kEps || c > hi + kEps) continue;
      bool clear = true;
      for (const scene::Opening& o : w.openings)
        clear = clear && std::abs(o.at - c) >= 0.5 * (o.width + width) + kDoorMinSpacing;
      if (clear) {
        at = c;
        break;
      }
    }
  }
  return at;
}

/// The plan's doors as openings of their walls, each on the longest stretch that holds it.
void place_doors(const FloorPlan& plan, std::vector<PendingWall>& walls, PlanResult* result) {
  const FloorPlanRules& rules = plan.rules;
  for (const DoorSpec& d : plan.doors) {
    double room = 0.0;
    PendingWall* host = door_host(walls, d, rules, &room);
    const double width = std::min(d.width, room);
    if (!host || width < rules.min_door) {
      ++result->doors_dropped;
      continue;
    }
    scene::Wall& w = host->wall;
    const std::optional<double> at = door_place(w, width, d.position, rules);
    if (!at) {
      ++result->doors_dropped;
      continue;
    }
    w.openings.push_back({*at, width, std::min(rules.door_height, w.height), 0.0});
    std::sort(w.openings.begin(), w.openings.end(),
              [](const scene::Opening& x, const scene::Opening& y) { return x.at < y.at; });
    ++result->doors_made;
  }
}

/// Half the thickness of the thickest wall or railing on each edge of each space's outline.
std::vector<std::vector<double>> face_offsets(const FloorPlan& plan, const Subdivision& sub) {
  std::vector<std::vector<double>> offsets(plan.spaces.size());
  for (std::size_t s = 0; s < plan.spaces.size(); ++s) offsets[s].assign(plan.spaces[s].outline.size(), 0.0);
  for (std::size_t i = 0; i < sub.pieces().size(); ++i) {
    const double half = 0.5 * thickness_of(sub.pieces()[i].kind, plan.rules);
    for (const auto& [s, e] : sub.edges_of(i)) offsets[s][e] = std::max(offsets[s][e], half);
  }
  return offsets;
}

/// The voids into the level, and the ground truth measured to the faces of what bounds each space.
void add_voids_and_rooms(const FloorPlan& plan, const Subdivision& sub, int level, scene::Scene* scene,
                         PlanResult* result) {
  scene::Level& lvl = scene->levels.at(level);
  const std::vector<std::vector<double>> offsets = face_offsets(plan, sub);
  result->room_of_space.assign(plan.spaces.size(), -1);
  for (std::size_t s = 0; s < plan.spaces.size(); ++s) {
    const Space& space = plan.spaces[s];
    result->faces.push_back(inset_polygon(space.outline, offsets[s]));
    if (space.kind == SpaceKind::kVoid) lvl.voids.push_back(space.outline);
    if (!is_ground_truth(space.kind) || !plan.ground_truth) continue;
    scene::Room r;
    r.name = space.name;
    r.level = level;
    r.polygon = result->faces.back();
    result->room_of_space[s] = static_cast<int>(scene->rooms.size());
    scene->rooms.push_back(r);
  }
}

}  // namespace

PlanResult add_floor_plan(const FloorPlan& plan, int level, scene::Scene* scene) {
  const Subdivision sub(plan);
  PlanResult result;
  const double ceiling = scene->levels.at(level).ceiling;
  std::vector<PendingWall> walls = walls_and_railings(sub, plan.rules, level, ceiling, scene);
  place_doors(plan, walls, &result);
  for (PendingWall& pw : walls) {
    const int index = static_cast<int>(scene->walls.size());
    result.walls.push_back(pw.a < 0 ? PlanWall{index, pw.b, -1} : PlanWall{index, pw.a, pw.b});
    scene->walls.push_back(pw.wall);
  }
  add_voids_and_rooms(plan, sub, level, scene, &result);
  return result;
}

Polygon2 inset_polygon(const Polygon2& poly, const std::vector<double>& offsets) {
  const std::size_t n = poly.size();
  const double orient = signed_area(poly) >= 0 ? 1.0 : -1.0;
  Polygon2 out(n);
  for (std::size_t i = 0; i < n; ++i) {
    // Vertex i joins edge i-1 (prev -> i) and edge i (i -> next).
    const std::size_t h = (i + n - 1) % n;
    const Vec2 d0 = (poly[i] - poly[h]).normalized(), d1 = (poly[(i + 1) % n] - poly[i]).normalized();
    const Vec2 n0 = orient * Vec2(-d0.y(), d0.x()), n1 = orient * Vec2(-d1.y(), d1.x());
    const Vec2 p0 = poly[h] + offsets[h] * n0, p1 = poly[i] + offsets[i] * n1;
    const double cross = d0.x() * d1.y() - d0.y() * d1.x();
    if (std::abs(cross) < 1e-9) {
      out[i] = poly[i] + std::max(offsets[h], offsets[i]) * n1;  // straight on: either line
      continue;
    }
    // p0 + t d0 = p1 + u d1
    const Vec2 w = p1 - p0;
    const double t = (w.x() * d1.y() - w.y() * d1.x()) / cross;
    out[i] = p0 + t * d0;
  }
  return out;
}

Polygon2 stacked_outline(double a0, double a1, double y0, double y1, double b0, double b1, double y2) {
  const Polygon2 raw = {{a0, y0}, {a1, y0}, {a1, y1}, {b1, y1}, {b1, y2}, {b0, y2}, {b0, y1}, {a0, y1}};
  Polygon2 out;
  for (std::size_t i = 0; i < raw.size(); ++i) {
    const Vec2& p = raw[i];
    if (!out.empty() && (out.back() - p).norm() < kEps) continue;
    out.push_back(p);
  }
  while (out.size() > 1 && (out.back() - out.front()).norm() < kEps) out.pop_back();
  // Drop vertices on a straight line (where the two rectangles share an end).
  Polygon2 simple;
  for (std::size_t i = 0; i < out.size(); ++i) {
    const Vec2& p = out[(i + out.size() - 1) % out.size()];
    const Vec2& q = out[(i + 1) % out.size()];
    const Vec2 d0 = out[i] - p, d1 = q - out[i];
    if (std::abs(d0.x() * d1.y() - d0.y() * d1.x()) < kEps * kEps && d0.dot(d1) > 0) continue;
    simple.push_back(out[i]);
  }
  return simple;
}

}  // namespace tsgraphs::generator
