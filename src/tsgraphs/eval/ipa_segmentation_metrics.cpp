#include "tsgraphs/eval/ipa_segmentation_metrics.hpp"

#include <algorithm>
#include <map>
#include <tuple>

namespace tsgraphs::eval {

IpaFigures ipa_precision_recall(const std::vector<CellRegion>& segments,
                                const std::vector<CellRegion>& truth) {
  const auto large = [](const std::vector<CellRegion>& regions) {
    std::vector<const CellRegion*> out;
    for (const CellRegion& r : regions)
      if (r.cells.size() > kIpaMaxSmallRegionCells) out.push_back(&r);
    return out;
  };
  const std::vector<const CellRegion*> seg = large(segments), gt = large(truth);
  // overlap[s][g]: cells shared; regions of different levels share none.
  std::vector<std::vector<double>> overlap(seg.size(), std::vector<double>(gt.size(), 0.0));
  for (std::size_t s = 0; s < seg.size(); ++s)
    for (std::size_t g = 0; g < gt.size(); ++g)
      if (seg[s]->level == gt[g]->level)
        overlap[s][g] = static_cast<double>(shared_cells(seg[s]->cells, gt[g]->cells));

  IpaFigures f;
  f.n_segments = static_cast<int>(seg.size());
  f.n_truth = static_cast<int>(gt.size());
  if (!seg.empty()) {
    double micro = 0.0, overlaps = 0.0, cells = 0.0;
    for (std::size_t s = 0; s < seg.size(); ++s) {
      double best = 0.0;
      for (std::size_t g = 0; g < gt.size(); ++g) best = std::max(best, overlap[s][g]);
      const double size = static_cast<double>(seg[s]->cells.size());
      micro += best / size;
      overlaps += best;
      cells += size;
    }
    f.precision_micro = micro / static_cast<double>(seg.size());
    f.precision_macro = overlaps / cells;
  }
  if (!gt.empty()) {
    double micro = 0.0, overlaps = 0.0, cells = 0.0;
    for (std::size_t g = 0; g < gt.size(); ++g) {
      double best = 0.0;
      for (std::size_t s = 0; s < seg.size(); ++s) best = std::max(best, overlap[s][g]);
      const double size = static_cast<double>(gt[g]->cells.size());
      micro += best / size;
      overlaps += best;
      cells += size;
    }
    f.recall_micro = micro / static_cast<double>(gt.size());
    f.recall_macro = overlaps / cells;
  }
  return f;
}

std::vector<CellRegion> regions_of(const std::vector<io::RoomTruth>& truth) {
  std::vector<CellRegion> out;
  for (const io::RoomTruth& t : truth) out.push_back({t.level, raster_cells(t.polygon)});
  return out;
}

std::vector<CellRegion> segments_of(const std::vector<LevelFootprint>& footprints,
                                    const std::vector<io::RoomTruth>& free_space) {
  std::map<std::string, std::vector<CellKey>> free;  // per level
  for (const io::RoomTruth& t : free_space)
    free[t.level] = cell_union(free[t.level], raster_cells(t.polygon));

  // Every (level, cell, area, index) claim; the first claim of a cell after sorting wins.
  std::map<std::string, int> level_ids;
  for (const LevelFootprint& f : footprints) level_ids.emplace(f.level, static_cast<int>(level_ids.size()));
  struct Claim {
    int level;
    CellKey cell;
    double area;
    std::size_t index;
  };
  std::vector<Claim> claims;
  for (std::size_t i = 0; i < footprints.size(); ++i) {
    const int level = level_ids.at(footprints[i].level);
    const double a = area(footprints[i].polygon);
    for (const CellKey c : raster_cells(footprints[i].polygon)) claims.push_back({level, c, a, i});
  }
  std::sort(claims.begin(), claims.end(), [](const Claim& p, const Claim& q) {
    return std::tie(p.level, p.cell, p.area, p.index) < std::tie(q.level, q.cell, q.area, q.index);
  });
  std::vector<CellRegion> out(footprints.size());
  for (std::size_t i = 0; i < footprints.size(); ++i) out[i].level = footprints[i].level;
  for (std::size_t k = 0; k < claims.size(); ++k) {
    if (k > 0 && claims[k].cell == claims[k - 1].cell && claims[k].level == claims[k - 1].level) continue;
    out[claims[k].index].cells.push_back(
        claims[k].cell);  // ascending: a footprint's claims are sorted by cell
  }
  for (CellRegion& r : out) {
    const auto it = free.find(r.level);
    r.cells = it == free.end() ? std::vector<CellKey>{} : cell_intersection(r.cells, it->second);
  }
  return out;
}

IpaFigures ipa_segmentation_metrics(const std::vector<LevelFootprint>& footprints,
                                    const std::vector<io::RoomTruth>& all_truth,
                                    const std::vector<io::RoomTruth>& counted_truth) {
  return ipa_precision_recall(segments_of(footprints, all_truth), regions_of(counted_truth));
}

}  // namespace tsgraphs::eval
