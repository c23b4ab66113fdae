#include "tsgraphs/eval/room_metrics.hpp"

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "tsgraphs/core/error.hpp"

namespace tsgraphs::eval {
namespace {

using nlohmann::json;

// ---- rooms_events.jsonl -------------------------------------------------------------------

// What is wrong with a field of one line; read_room_events adds the file and line.
struct FieldError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

const json& field(const json& obj, const char* key, const std::string& where) {
  const auto it = obj.find(key);
  if (it == obj.end()) throw FieldError("missing key '" + where + key + "'");
  return *it;
}

double number_of(const json& obj, const char* key, const std::string& where = "") {
  const json& v = field(obj, key, where);
  if (!v.is_number()) throw FieldError("'" + where + key + "' must be a number");
  return v.get<double>();
}

int int_of(const json& v, const std::string& name) {
  if (!v.is_number_integer()) throw FieldError("'" + name + "' must be an integer");
  const std::int64_t i = v.get<std::int64_t>();
  if (i < std::numeric_limits<int>::min() || i > std::numeric_limits<int>::max())
    throw FieldError("'" + name + "' is out of range");
  return static_cast<int>(i);
}

Vec2 vec2_of(const json& obj, const char* key, const std::string& where = "") {
  const json& v = field(obj, key, where);
  if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number())
    throw FieldError("'" + where + key + "' must be [x, y]");
  return {v[0].get<double>(), v[1].get<double>()};
}

RoomEvent event_of(const json& j) {
  if (!j.is_object()) throw FieldError("expected a JSON object");
  RoomEvent e;
  e.t = number_of(j, "t");
  e.lap = int_of(field(j, "lap", ""), "lap");
  if (e.lap < 1) throw FieldError("'lap' counts from 1");
  e.room_id = int_of(field(j, "room_id", ""), "room_id");
  const json& is_new = field(j, "new", "");
  if (!is_new.is_boolean()) throw FieldError("'new' must be true or false");
  e.is_new = is_new.get<bool>();
  e.level = int_of(field(j, "level", ""), "level");
  e.center = vec2_of(j, "center");
  const json& rect = field(j, "rect", "");
  if (!rect.is_object()) throw FieldError("'rect' must be an object");
  e.rect.center = vec2_of(rect, "center", "rect.");
  e.rect.size = vec2_of(rect, "size", "rect.");
  if (e.rect.size.x() < 0.0 || e.rect.size.y() < 0.0) throw FieldError("'rect.size' must not be negative");
  e.rect.yaw = number_of(rect, "yaw", "rect.");
  const json& walls = field(j, "walls", "");
  if (!walls.is_array()) throw FieldError("'walls' must be an array of wall ids");
  for (const json& w : walls) e.walls.push_back(int_of(w, "walls[]"));
  const json& kind = field(j, "kind", "");
  if (!kind.is_string() || (kind != "room" && kind != "corridor"))
    throw FieldError("'kind' must be \"room\" or \"corridor\"");
  e.kind = kind.get<std::string>();
  return e;
}

// ---- pairing ------------------------------------------------------------------------------

struct Candidate {
  double score;
  std::size_t a, b;
};

// One-to-one pairs taken greedily by the highest score first; ties by a, then b, so the result
// does not depend on the sort's stability.
std::vector<Candidate> greedy_pairs(std::vector<Candidate> candidates, std::size_t na, std::size_t nb) {
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& p, const Candidate& q) {
    if (p.score != q.score) return p.score > q.score;
    return p.a != q.a ? p.a < q.a : p.b < q.b;
  });
  std::vector<bool> used_a(na, false), used_b(nb, false);
  std::vector<Candidate> pairs;
  for (const Candidate& c : candidates) {
    if (used_a[c.a] || used_b[c.b]) continue;
    used_a[c.a] = used_b[c.b] = true;
    pairs.push_back(c);
  }
  return pairs;
}

}  // namespace

std::string format_room_event(const RoomEvent& e) {
  // ordered_json keeps the keys in metrics.md's order.
  nlohmann::ordered_json j;
  j["t"] = e.t;
  j["lap"] = e.lap;
  j["room_id"] = e.room_id;
  j["new"] = e.is_new;
  j["level"] = e.level;
  j["center"] = {e.center.x(), e.center.y()};
  nlohmann::ordered_json rect;
  rect["center"] = {e.rect.center.x(), e.rect.center.y()};
  rect["size"] = {e.rect.size.x(), e.rect.size.y()};
  rect["yaw"] = e.rect.yaw;
  j["rect"] = rect;
  j["walls"] = e.walls;
  j["kind"] = e.kind;
  return j.dump();
}

std::vector<RoomEvent> read_room_events(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw input_error(path, 0, "cannot open file");
  std::vector<RoomEvent> events;
  std::string text;
  int line_no = 0;
  while (std::getline(in, text)) {
    ++line_no;
    if (text.find_first_not_of(" \t\r") == std::string::npos) continue;
    json j;
    try {
      j = json::parse(text);
    } catch (const json::parse_error& err) {
      throw input_error(path, line_no, std::string("malformed JSON: ") + err.what());
    }
    try {
      events.push_back(event_of(j));
    } catch (const FieldError& err) {
      throw input_error(path, line_no, err.what());
    }
  }
  return events;
}

Consistency consistency_between(const std::vector<DetectedRoom>& first, const std::vector<DetectedRoom>& second) {
  std::vector<Candidate> candidates;
  for (std::size_t a = 0; a < first.size(); ++a) {
    for (std::size_t b = 0; b < second.size(); ++b) {
      if (first[a].level != second[b].level) continue;
      const double d = dice(first[a].rect, second[b].rect);
      if (d >= kPairMinDice) candidates.push_back({d, a, b});
    }
  }
  Consistency c;
  c.N1st = static_cast<int>(first.size());
  c.N2nd = static_cast<int>(second.size());
  double sum_dice = 0.0, sum_dist = 0.0;
  for (const Candidate& p : greedy_pairs(std::move(candidates), first.size(), second.size())) {
    const double dist = (first[p.a].rect.center - second[p.b].rect.center).norm();
    c.pairs.push_back({p.a, p.b, p.score, dist});
    sum_dice += p.score;
    sum_dist += dist;
  }
  c.N_re = static_cast<int>(c.pairs.size());
  c.f_re = c.N1st > 0 ? static_cast<double>(c.N_re) / c.N1st : 0.0;
  if (c.N_re > 0) {
    c.dcs = sum_dice / c.N_re;
    c.d_center = sum_dist / c.N_re;
  }
  return c;
}

Consistency consistency(const std::vector<RoomEvent>& events) {
  std::vector<DetectedRoom> lap1, lap2;
  for (const RoomEvent& e : events) {
    if (e.lap == 1) lap1.push_back({e.rect, std::to_string(e.level)});
    if (e.lap == 2) lap2.push_back({e.rect, std::to_string(e.level)});
  }
  return consistency_between(lap1, lap2);
}

double intersection_area(const OrientedRect& rect, const Polygon2& polygon) {
  if (rect.area() <= 0.0 || polygon.size() < 3) return 0.0;
  // The rectangle is convex, so it can clip the polygon even where the polygon is not.
  return area(clip_to_convex(polygon, rect.corners()));
}

double iou(const OrientedRect& rect, const Polygon2& polygon) {
  const double inter = intersection_area(rect, polygon);
  const double uni = rect.area() + area(polygon) - inter;
  return uni > 0.0 ? inter / uni : 0.0;
}

RoomsVsTruth rooms_vs_truth(const std::vector<DetectedRoom>& detected, const std::vector<io::RoomTruth>& truth) {
  const std::size_t nd = detected.size(), nt = truth.size();
  std::vector<double> truth_area(nt);
  for (std::size_t g = 0; g < nt; ++g) truth_area[g] = area(truth[g].polygon);
  // Shared areas; rooms of different levels share none.
  std::vector<std::vector<double>> inter(nd, std::vector<double>(nt, 0.0));
  for (std::size_t d = 0; d < nd; ++d)
    for (std::size_t g = 0; g < nt; ++g)
      if (detected[d].level == truth[g].level) inter[d][g] = intersection_area(detected[d].rect, truth[g].polygon);

  // Greedy matching on the pairs at the threshold only: lower pairs are taken after every
  // pair above it, so they could not change those.
  std::vector<Candidate> candidates;
  for (std::size_t d = 0; d < nd; ++d) {
    for (std::size_t g = 0; g < nt; ++g) {
      const double uni = detected[d].rect.area() + truth_area[g] - inter[d][g];
      const double score = uni > 0.0 ? inter[d][g] / uni : 0.0;
      if (score >= kMatchMinIou) candidates.push_back({score, d, g});
    }
  }
  RoomsVsTruth r;
  r.n_rooms_final = static_cast<int>(nd);
  double sum_iou = 0.0;
  for (const Candidate& p : greedy_pairs(std::move(candidates), nd, nt)) {
    ++r.n_matched;
    sum_iou += p.score;
  }
  if (nd > 0) r.precision = static_cast<double>(r.n_matched) / nd;
  if (nt > 0) r.recall = static_cast<double>(r.n_matched) / nt;
  if (r.precision && r.recall) {
    const double s = *r.precision + *r.recall;
    r.f1 = s > 0.0 ? 2.0 * *r.precision * *r.recall / s : 0.0;
  }
  if (r.n_matched > 0) r.mean_iou = sum_iou / r.n_matched;

  auto covers = [&](std::size_t d, std::size_t g) {
    return truth_area[g] > 0.0 && inter[d][g] >= kSegmentMinCover * truth_area[g];
  };
  for (std::size_t d = 0; d < nd; ++d) {
    int n = 0;
    for (std::size_t g = 0; g < nt; ++g) n += covers(d, g) ? 1 : 0;
    if (n >= 2) ++r.under_segmented;
  }
  for (std::size_t g = 0; g < nt; ++g) {
    int n = 0;
    for (std::size_t d = 0; d < nd; ++d) n += covers(d, g) ? 1 : 0;
    if (n >= 2) ++r.over_segmented;
  }
  return r;
}

std::vector<io::RoomTruth> visited_rooms(const std::vector<io::RoomTruth>& truth, const std::vector<Pose3>& poses) {
  std::vector<bool> visited(truth.size(), false);
  for (const Pose3& pose : poses) {
    const Eigen::Vector3d p = pose.translation();
    double floor = -std::numeric_limits<double>::infinity();
    for (const io::RoomTruth& t : truth)
      if (t.elevation <= p.z()) floor = std::max(floor, t.elevation);
    for (std::size_t i = 0; i < truth.size(); ++i)
      if (!visited[i] && truth[i].elevation == floor && contains(truth[i].polygon, p.head<2>())) visited[i] = true;
  }
  std::vector<io::RoomTruth> out;
  for (std::size_t i = 0; i < truth.size(); ++i)
    if (visited[i]) out.push_back(truth[i]);
  return out;
}

}  // namespace tsgraphs::eval
