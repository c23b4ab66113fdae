#include "tsgraphs/scene/survey_path.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <queue>
#include <stdexcept>
#include <unordered_map>

#include "tsgraphs/scene/scene_geometry.hpp"
#include "tsgraphs/scene/trajectory.hpp"

namespace tsgraphs::scene {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kMinClearanceForCost = 0.05;  // m: the centre weight's floor, so costs stay finite
constexpr double kCollinearSin = 1e-3;         // a waypoint turning less than this (sin) is dropped
constexpr double kLevelMatch = 0.3;            // m between a pose's floor height and a level's surface

/// The planning graph: every cell of every grid, cells joined to their 8 neighbours and, in
/// a link's area, to the same cell of the linked grid.
class PlanningGraph {
 public:
  PlanningGraph(const std::vector<WalkableGrid>& grids, const std::vector<GridLink>& links,
                double min_clearance, double centre_weight)
      : n_(grids.front().frame.size()), frame_(grids.front().frame) {
    for (const WalkableGrid& g : grids) {
      if (g.frame.cols != frame_.cols || g.frame.rows != frame_.rows ||
          g.frame.resolution != frame_.resolution || g.frame.origin != frame_.origin)
        throw std::invalid_argument("survey path: the grids of all levels must share one frame");
    }
    passable_.assign(grids.size() * n_, 0);
    weight_.assign(grids.size() * n_, 1.0f);
    for (std::size_t g = 0; g < grids.size(); ++g) {
      for (std::size_t i = 0; i < n_; ++i) {
        passable_[g * n_ + i] = grids[g].free[i] != 0 && grids[g].clearance[i] >= min_clearance;
        weight_[g * n_ + i] = static_cast<float>(
            1.0 + centre_weight / std::max<double>(grids[g].clearance[i], kMinClearanceForCost));
      }
    }
    link_.assign(grids.size() * n_, -1);
    for (const GridLink& l : links) {
      for (int r = 0; r < frame_.rows; ++r) {
        for (int c = 0; c < frame_.cols; ++c) {
          if (!contains(l.area, frame_.center(c, r))) continue;
          const std::size_t i = frame_.index(c, r);
          link_[l.grid_a * n_ + i] = l.grid_b;
          link_[l.grid_b * n_ + i] = l.grid_a;
        }
      }
    }
  }

  std::size_t num_nodes() const { return passable_.size(); }
  bool passable(std::size_t node) const { return passable_[node] != 0; }
  int grid_of(std::size_t node) const { return static_cast<int>(node / n_); }
  std::size_t cell_of(std::size_t node) const { return node % n_; }
  Vec2 xy(std::size_t node) const { return frame_.center(cell_of(node)); }
  const GridFrame& frame() const { return frame_; }
  bool node_at(int grid, const Vec2& p, std::size_t* node) const {
    int c, r;
    if (!frame_.cell_of(p, &c, &r)) return false;
    *node = grid * n_ + frame_.index(c, r);
    return true;
  }
  bool passable_at(int grid, const Vec2& p) const {
    std::size_t node;
    return node_at(grid, p, &node) && passable(node);
  }

  /// Calls f(neighbour, cost) for each passable neighbour of a passable node.
  template <class F>
  void for_each_neighbour(std::size_t node, F&& f) const {
    const int g = grid_of(node);
    const std::size_t cell = cell_of(node);
    const int c = static_cast<int>(cell % frame_.cols), r = static_cast<int>(cell / frame_.cols);
    const double w0 = weight_[node];
    static const int kDc[8] = {1, -1, 0, 0, 1, 1, -1, -1};
    static const int kDr[8] = {0, 0, 1, -1, 1, -1, 1, -1};
    for (int k = 0; k < 8; ++k) {
      const int cc = c + kDc[k], rr = r + kDr[k];
      if (!frame_.inside(cc, rr)) continue;
      const std::size_t nb = g * n_ + frame_.index(cc, rr);
      if (!passable(nb)) continue;
      // Diagonal steps only where both straight neighbours are open: no cutting a corner.
      if (k >= 4 && (!passable(g * n_ + frame_.index(cc, r)) || !passable(g * n_ + frame_.index(c, rr))))
        continue;
      const double len = (k >= 4 ? M_SQRT2 : 1.0) * frame_.resolution;
      f(nb, 0.5 * len * (w0 + weight_[nb]));
    }
    const int other = link_[node];
    if (other >= 0) {
      const std::size_t nb = other * n_ + cell;
      if (passable(nb)) f(nb, 0.0);
    }
  }

 private:
  std::size_t n_;
  GridFrame frame_;
  std::vector<std::uint8_t> passable_;
  std::vector<int> link_;
  std::vector<float> weight_;  // cost per metre of a step leaving each node
};

using QueueItem = std::pair<double, std::size_t>;

/// Costs from `source` to each of `targets` (kInf where unreachable): Dijkstra, stopped once
/// every target is settled.
std::vector<double> costs_to(const PlanningGraph& graph, std::size_t source,
                             const std::vector<std::size_t>& targets) {
  std::vector<double> cost(graph.num_nodes(), kInf);
  std::vector<std::uint8_t> is_target(graph.num_nodes(), 0);
  for (std::size_t t : targets) is_target[t] = 1;
  std::size_t left = 0;
  for (std::size_t t : targets) left += is_target[t] == 1 ? (is_target[t] = 2, 1) : 0;  // distinct targets
  std::priority_queue<QueueItem, std::vector<QueueItem>, std::greater<>> queue;
  cost[source] = 0.0;
  queue.push({0.0, source});
  while (!queue.empty() && left > 0) {
    // Plain names, not a structured binding: the lambda below captures them (C++17).
    const double c = queue.top().first;
    const std::size_t node = queue.top().second;
    queue.pop();
    if (c > cost[node]) continue;
    if (is_target[node] == 2) {
      is_target[node] = 3;
      --left;
    }
    graph.for_each_neighbour(node, [&](std::size_t nb, double step) {
      if (c + step < cost[nb]) {
        cost[nb] = c + step;
        queue.push({cost[nb], nb});
      }
    });
  }
  std::vector<double> out;
  for (std::size_t t : targets) out.push_back(cost[t]);
  return out;
}

/// The cheapest path from `source` to `target` (A*, the straight-line distance as the bound:
/// every step costs at least its length); empty when there is none.
std::vector<std::size_t> cheapest_path(const PlanningGraph& graph, std::size_t source, std::size_t target) {
  std::unordered_map<std::size_t, double> cost;
  std::unordered_map<std::size_t, std::size_t> parent;
  const Vec2 goal = graph.xy(target);
  std::priority_queue<QueueItem, std::vector<QueueItem>, std::greater<>> queue;
  cost[source] = 0.0;
  queue.push({(graph.xy(source) - goal).norm(), source});
  while (!queue.empty()) {
    const double f = queue.top().first;
    const std::size_t node = queue.top().second;
    queue.pop();
    const double c = cost[node];
    if (f > c + (graph.xy(node) - goal).norm() + 1e-12) continue;  // a stale entry
    if (node == target) break;
    graph.for_each_neighbour(node, [&](std::size_t nb, double step) {
      const auto it = cost.find(nb);
      if (it != cost.end() && it->second <= c + step) return;
      cost[nb] = c + step;
      parent[nb] = node;
      queue.push({c + step + (graph.xy(nb) - goal).norm(), nb});
    });
  }
  if (!cost.count(target)) return {};
  std::vector<std::size_t> chain = {target};
  while (chain.back() != source) chain.push_back(parent.at(chain.back()));
  std::reverse(chain.begin(), chain.end());
  return chain;
}

/// Visiting order: nearest neighbour from stop 0, then 2-opt on the closed tour.
std::vector<std::size_t> order_stops(const std::vector<std::vector<double>>& cost) {
  const std::size_t n = cost.size();
  std::vector<std::size_t> tour = {0};
  std::vector<bool> used(n, false);
  used[0] = true;
  for (std::size_t k = 1; k < n; ++k) {
    std::size_t best = n;
    for (std::size_t j = 0; j < n; ++j) {
      if (!used[j] && (best == n || cost[tour.back()][j] < cost[tour.back()][best])) best = j;
    }
    used[best] = true;
    tour.push_back(best);
  }
  const auto c = [&](std::size_t a, std::size_t b) { return 0.5 * (cost[a][b] + cost[b][a]); };
  for (bool improved = n > 3; improved;) {
    improved = false;
    for (std::size_t i = 0; i + 2 < n; ++i) {
      for (std::size_t j = i + 2; j < n; ++j) {
        const std::size_t a = tour[i], b = tour[i + 1], d = tour[j], e = tour[(j + 1) % n];
        if (a == e) continue;
        if (c(a, d) + c(b, e) < c(a, b) + c(d, e) - 1e-9) {
          std::reverse(tour.begin() + static_cast<long>(i) + 1, tour.begin() + static_cast<long>(j) + 1);
          improved = true;
        }
      }
    }
  }
  return tour;
}

/// True when the straight line a-b on `grid` keeps to passable cells (sampled every half cell).
bool line_passable(const PlanningGraph& graph, int grid, const Vec2& a, const Vec2& b) {
  const double step = 0.5 * graph.frame().resolution;
  const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / step)));
  for (int k = 0; k <= n; ++k) {
    if (!graph.passable_at(grid, a + (b - a) * (static_cast<double>(k) / n))) return false;
  }
  return true;
}

/// Douglas-Peucker on points[i..j] of one grid, splitting also where a straight leg would
/// leave the passable cells; appends the kept points after i (i itself is already out).
void simplify(const PlanningGraph& graph, int grid, const std::vector<Vec2>& pts, std::size_t i,
              std::size_t j, double tolerance, std::vector<Vec2>* out) {
  if (j <= i + 1) {
    if (j > i) out->push_back(pts[j]);
    return;
  }
  double worst = -1.0;
  std::size_t at = i + 1;
  for (std::size_t k = i + 1; k < j; ++k) {
    const double d = distance_to_segment(pts[k], pts[i], pts[j]);
    if (d > worst) {
      worst = d;
      at = k;
    }
  }
  if (worst <= tolerance && line_passable(graph, grid, pts[i], pts[j])) {
    out->push_back(pts[j]);
    return;
  }
  simplify(graph, grid, pts, i, at, tolerance, out);
  simplify(graph, grid, pts, at, j, tolerance, out);
}

struct Sample {
  double clearance;
  Vec2 xy;
  int level;
};

std::vector<Sample> sample_path(const Scene& scene, const ClearanceAt& clearance_at, double step) {
  const Trajectory trajectory(scene);
  const double dt = step / scene.trajectory.speed;
  std::vector<Sample> out;
  int level = scene.trajectory.level;
  for (double t = 0.0;; t += dt) {
    const double tt = std::min(t, trajectory.duration());
    const Pose3 p = trajectory.body_pose(tt);
    const Vec2 xy = p.translation().head<2>();
    const double floor_z = p.translation().z() - scene.sensor.mount_height;
    level = level_under(scene, xy, floor_z, kLevelMatch, level);
    out.push_back({clearance_at(xy, floor_z, level), xy, level});
    if (tt >= trajectory.duration()) break;
  }
  return out;
}

}  // namespace

bool most_interior_point(const WalkableGrid& grid, const Polygon2& region, Vec2* point) {
  double best = -1.0;
  Vec2 lo = Vec2::Constant(kInf), hi = -lo;
  for (const Vec2& p : region) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const GridFrame& f = grid.frame;
  const int c0 = std::max(0, static_cast<int>(std::floor((lo.x() - f.origin.x()) / f.resolution)));
  const int c1 = std::min(f.cols - 1, static_cast<int>(std::floor((hi.x() - f.origin.x()) / f.resolution)));
  const int r0 = std::max(0, static_cast<int>(std::floor((lo.y() - f.origin.y()) / f.resolution)));
  const int r1 = std::min(f.rows - 1, static_cast<int>(std::floor((hi.y() - f.origin.y()) / f.resolution)));
  for (int r = r0; r <= r1; ++r) {
    for (int c = c0; c <= c1; ++c) {
      const std::size_t i = f.index(c, r);
      if (!grid.free[i] || grid.clearance[i] <= best || !contains(region, f.center(c, r))) continue;
      best = grid.clearance[i];
      *point = f.center(c, r);
    }
  }
  return best >= 0.0;
}

std::vector<Waypoint> plan_survey(const std::vector<WalkableGrid>& grids, const std::vector<GridLink>& links,
                                  const std::vector<SurveyStop>& stops, const SurveyConfig& config,
                                  const std::function<std::string(std::size_t)>& describe) {
  if (grids.empty() || stops.empty()) throw std::invalid_argument("survey path: no grid or no stop");
  const auto name = [&](std::size_t i) { return describe ? describe(i) : "stop " + std::to_string(i); };
  const double min_clearance = config.clearance + config.plan_margin_cells * grids.front().frame.resolution;
  const PlanningGraph graph(grids, links, min_clearance, config.centre_weight);
  std::vector<std::size_t> nodes(stops.size());
  for (std::size_t i = 0; i < stops.size(); ++i) {
    const SurveyStop& s = stops[i];
    if (s.grid < 0 || s.grid >= static_cast<int>(grids.size()) || !graph.node_at(s.grid, s.xy, &nodes[i]) ||
        !graph.passable(nodes[i])) {
      throw std::invalid_argument("survey path: " + name(i) + " is not " + std::to_string(min_clearance) +
                                  " m clear of every obstacle");
    }
  }
  // Path costs between every pair of stops.
  std::vector<std::vector<double>> cost(stops.size(), std::vector<double>(stops.size(), 0.0));
  for (std::size_t i = 0; i < stops.size(); ++i) {
    const std::vector<double> c = costs_to(graph, nodes[i], nodes);
    for (std::size_t j = 0; j < stops.size(); ++j) {
      cost[i][j] = c[j];
      if (!std::isfinite(cost[i][j]))
        throw std::invalid_argument("survey path: " + name(j) + " cannot be reached from " + name(i) +
                                    " with " + std::to_string(config.clearance) + " m clearance");
    }
  }
  const std::vector<std::size_t> tour = order_stops(cost);

  std::vector<Waypoint> lap;
  const auto push = [&](const Vec2& xy, int grid) {
    const int level = grids[grid].level;
    if (!lap.empty() && (lap.back().xy - xy).norm() < 1e-9) {
      lap.back().level = level;  // a change of grid at this point: the new level
      return;
    }
    lap.push_back({xy, level, 0});
  };
  push(stops[tour[0]].xy, stops[tour[0]].grid);
  for (std::size_t k = 0; k < tour.size(); ++k) {
    const std::size_t from = nodes[tour[k]], to = nodes[tour[(k + 1) % tour.size()]];
    if (from == to) continue;
    const std::vector<std::size_t> chain = cheapest_path(graph, from, to);
    // Simplify each run on one grid; the stops keep their exact places.
    std::size_t a = 0;
    while (a + 1 < chain.size()) {
      std::size_t b = a;
      while (b + 1 < chain.size() && graph.grid_of(chain[b + 1]) == graph.grid_of(chain[a])) ++b;
      const int grid = graph.grid_of(chain[a]);
      std::vector<Vec2> pts;
      for (std::size_t i = a; i <= b; ++i) pts.push_back(graph.xy(chain[i]));
      if (a == 0) pts.front() = stops[tour[k]].xy;
      if (b + 1 == chain.size()) pts.back() = stops[tour[(k + 1) % tour.size()]].xy;
      std::vector<Vec2> kept;
      simplify(graph, grid, pts, 0, pts.size() - 1, config.simplify_tolerance, &kept);
      for (const Vec2& p : kept) push(p, grid);
      if (b + 1 < chain.size())
        push(lap.back().xy, graph.grid_of(chain[b + 1]));  // cross to the linked grid here
      a = b + 1 < chain.size() ? b + 1 : b;
    }
  }
  if (lap.size() > 1 && (lap.back().xy - lap.front().xy).norm() < 1e-9)
    lap.pop_back();  // closed: returns by itself
  // Drop waypoints on a straight line (not where the level changes).
  std::vector<Waypoint> out;
  for (std::size_t i = 0; i < lap.size(); ++i) {
    const Waypoint& w = lap[i];
    if (i > 0 && i + 1 < lap.size() && !out.empty() && out.back().level == w.level &&
        lap[i + 1].level == w.level) {
      const Vec2 d0 = (w.xy - out.back().xy).normalized(), d1 = (lap[i + 1].xy - w.xy).normalized();
      if (std::abs(d0.x() * d1.y() - d0.y() * d1.x()) < kCollinearSin && d0.dot(d1) > 0.0) continue;
    }
    out.push_back(w);
  }
  return out;
}

PathClearance path_clearance(const Scene& scene, const ClearanceAt& clearance_at, double step) {
  PathClearance worst;
  worst.min_clearance = kInf;
  for (const Sample& s : sample_path(scene, clearance_at, step)) {
    if (s.clearance < worst.min_clearance) worst = {s.clearance, s.xy, s.level};
  }
  return worst;
}

double keep_clearance_on_turns(Scene* scene, const ClearanceAt& clearance_at, const SurveyConfig& config) {
  std::vector<Waypoint>& wps = scene->trajectory.waypoints;
  std::vector<bool> turned(wps.size(), false);  // corners already made turns in place
  for (int fixes = 0; fixes < config.max_turn_fixes;) {
    // The corner nearest to each place that comes too close.
    std::vector<bool> fix(wps.size(), false);
    bool any = false;
    for (const Sample& s : sample_path(*scene, clearance_at, config.check_step)) {
      if (s.clearance >= config.clearance) continue;
      std::size_t nearest = 0;
      for (std::size_t i = 1; i < wps.size(); ++i) {
        if ((wps[i].xy - s.xy).norm() < (wps[nearest].xy - s.xy).norm()) nearest = i;
      }
      if (!turned[nearest]) {
        fix[nearest] = true;
        any = true;
      }
    }
    if (!any) break;
    std::vector<Waypoint> next;
    std::vector<bool> next_turned;
    std::optional<Waypoint> end_stub;  // the corner at a lap's start: its stub ends the lap
    for (std::size_t i = 0; i < wps.size(); ++i) {
      const std::size_t prev = i == 0 ? wps.size() - 1 : i - 1;
      if (fix[i] && (i > 0 || scene->trajectory.closed)) {
        const Vec2 back = wps[prev].xy - wps[i].xy;
        Waypoint stub = wps[i];
        stub.xy = wps[i].xy + std::min(config.stub_length, 0.25 * back.norm()) * back.normalized();
        if (i == 0) {
          end_stub = stub;
        } else {
          next.push_back(stub);
          next_turned.push_back(true);
        }
        ++fixes;
      }
      next.push_back(wps[i]);
      next_turned.push_back(turned[i] || fix[i]);
    }
    if (end_stub) {
      next.push_back(*end_stub);
      next_turned.push_back(true);
    }
    wps = std::move(next);
    turned = std::move(next_turned);
  }
  return path_clearance(*scene, clearance_at, config.check_step).min_clearance;
}

}  // namespace tsgraphs::scene
