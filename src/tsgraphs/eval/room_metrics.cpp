#include "tsgraphs/eval/room_metrics.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>

namespace tsgraphs::eval {
namespace {

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

Consistency consistency_between(const std::vector<DetectedRoom>& first,
                                const std::vector<DetectedRoom>& second) {
  std::vector<Candidate> candidates;
  std::vector<Polygon2> fa, fb;
  for (const DetectedRoom& r : first) fa.push_back(r.footprint());
  for (const DetectedRoom& r : second) fb.push_back(r.footprint());
  for (std::size_t a = 0; a < first.size(); ++a) {
    for (std::size_t b = 0; b < second.size(); ++b) {
      if (first[a].level != second[b].level) continue;
      const double d = dice(fa[a], fb[b]);
      if (d >= kPairMinDice) candidates.push_back({d, a, b});
    }
  }
  Consistency c;
  c.N1st = static_cast<int>(first.size());
  c.N2nd = static_cast<int>(second.size());
  double sum_dice = 0.0, sum_dist = 0.0;
  for (const Candidate& p : greedy_pairs(std::move(candidates), first.size(), second.size())) {
    const double dist = (first[p.a].center() - second[p.b].center()).norm();
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

Consistency consistency(const std::vector<io::RoomEvent>& events) {
  std::vector<DetectedRoom> lap1, lap2;
  for (const io::RoomEvent& e : events) {
    if (e.lap == 1) lap1.push_back({e.rect, std::to_string(e.level), e.polygon});
    if (e.lap == 2) lap2.push_back({e.rect, std::to_string(e.level), e.polygon});
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

RoomsVsTruth rooms_vs_truth(const std::vector<DetectedRoom>& detected,
                            const std::vector<io::RoomTruth>& truth) {
  const std::size_t nd = detected.size(), nt = truth.size();
  std::vector<double> truth_area(nt);
  std::vector<Polygon2> footprint(nd);
  std::vector<double> detected_area(nd);
  for (std::size_t d = 0; d < nd; ++d) {
    footprint[d] = detected[d].footprint();
    detected_area[d] = area(footprint[d]);
  }
  for (std::size_t g = 0; g < nt; ++g) truth_area[g] = area(truth[g].polygon);
  // Shared areas; rooms of different levels share none.
  std::vector<std::vector<double>> inter(nd, std::vector<double>(nt, 0.0));
  for (std::size_t d = 0; d < nd; ++d)
    for (std::size_t g = 0; g < nt; ++g)
      if (detected[d].level == truth[g].level)
        inter[d][g] = tsgraphs::intersection_area(footprint[d], truth[g].polygon);

  // Greedy matching on the pairs at the threshold only: lower pairs are taken after every
  // pair above it, so they could not change those.
  std::vector<Candidate> candidates;
  for (std::size_t d = 0; d < nd; ++d) {
    for (std::size_t g = 0; g < nt; ++g) {
      const double uni = detected_area[d] + truth_area[g] - inter[d][g];
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

std::vector<io::RoomTruth> visited_rooms(const std::vector<io::RoomTruth>& truth,
                                         const std::vector<Pose3>& poses) {
  std::vector<bool> visited(truth.size(), false);
  for (const Pose3& pose : poses) {
    const Eigen::Vector3d p = pose.translation();
    double floor = -std::numeric_limits<double>::infinity();
    for (const io::RoomTruth& t : truth)
      if (t.elevation <= p.z()) floor = std::max(floor, t.elevation);
    for (std::size_t i = 0; i < truth.size(); ++i)
      if (!visited[i] && truth[i].elevation == floor && contains(truth[i].polygon, p.head<2>()))
        visited[i] = true;
  }
  std::vector<io::RoomTruth> out;
  for (std::size_t i = 0; i < truth.size(); ++i)
    if (visited[i]) out.push_back(truth[i]);
  return out;
}

}  // namespace tsgraphs::eval
