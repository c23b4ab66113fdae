#include "tsgraphs/eval/label_metrics.hpp"

#include <algorithm>
#include <map>
#include <stdexcept>
#include <tuple>

#include "tsgraphs/eval/room_metrics.hpp"

namespace tsgraphs::eval {

std::vector<CellRegion> regions_of_labels(const std::vector<int>& labels, int cols) {
  int n = 0;
  for (int l : labels) n = std::max(n, l + 1);
  std::vector<CellRegion> out(static_cast<std::size_t>(n));
  // Index order is row by row, as cell keys are: each region's keys come out ascending.
  for (std::size_t i = 0; i < labels.size(); ++i)
    if (labels[i] >= 0)
      out[static_cast<std::size_t>(labels[i])].cells.push_back(
          cell_key(static_cast<int>(i % static_cast<std::size_t>(cols)),
                   static_cast<int>(i / static_cast<std::size_t>(cols))));
  return out;
}

namespace {

/// Room pairs of the two labellings, one to one, greedy by IoU (the regions are those of more
/// than kIpaMaxSmallRegionCells cells).
LabelRoomFigures match_rooms(const std::vector<int>& segments, const std::vector<int>& truth) {
  std::map<int, std::size_t> seg_size, truth_size;
  std::map<std::pair<int, int>, std::size_t> shared;
  for (std::size_t i = 0; i < segments.size(); ++i) {
    if (segments[i] >= 0) ++seg_size[segments[i]];
    if (truth[i] >= 0) ++truth_size[truth[i]];
    if (segments[i] >= 0 && truth[i] >= 0) ++shared[{segments[i], truth[i]}];
  }
  const auto large = [](const std::map<int, std::size_t>& sizes, int k) {
    const auto it = sizes.find(k);
    return it != sizes.end() && it->second > kIpaMaxSmallRegionCells;
  };
  LabelRoomFigures f;
  for (const auto& [k, n] : seg_size) f.n_segments += n > kIpaMaxSmallRegionCells ? 1 : 0;
  for (const auto& [k, n] : truth_size) f.n_truth += n > kIpaMaxSmallRegionCells ? 1 : 0;
  std::vector<std::tuple<double, int, int>> candidates;  // (-IoU, segment, truth)
  for (const auto& [pair, n] : shared) {
    if (!large(seg_size, pair.first) || !large(truth_size, pair.second)) continue;
    const double iou =
        static_cast<double>(n) / static_cast<double>(seg_size[pair.first] + truth_size[pair.second] - n);
    if (iou >= kMatchMinIou) candidates.emplace_back(-iou, pair.first, pair.second);
  }
  std::sort(candidates.begin(), candidates.end());
  std::map<int, bool> seg_taken, truth_taken;
  double iou_sum = 0.0;
  for (const auto& [neg_iou, s, t] : candidates) {
    if (seg_taken[s] || truth_taken[t]) continue;
    seg_taken[s] = truth_taken[t] = true;
    ++f.n_matched;
    iou_sum -= neg_iou;
  }
  if (f.n_segments > 0) f.precision = static_cast<double>(f.n_matched) / f.n_segments;
  if (f.n_truth > 0) f.recall = static_cast<double>(f.n_matched) / f.n_truth;
  if (f.precision && f.recall)
    f.f1 = *f.precision + *f.recall > 0.0 ? 2.0 * *f.precision * *f.recall / (*f.precision + *f.recall) : 0.0;
  if (f.n_matched > 0) f.mean_iou = iou_sum / f.n_matched;
  return f;
}

}  // namespace

LabelFigures compare_labels(const std::vector<int>& segments, const std::vector<int>& truth, int cols) {
  if (segments.size() != truth.size() || cols <= 0 || segments.size() % static_cast<std::size_t>(cols) != 0)
    throw std::invalid_argument("compare_labels: the two labellings are not of one raster");
  LabelFigures out;
  out.ipa = ipa_precision_recall(regions_of_labels(segments, cols), regions_of_labels(truth, cols));
  out.rooms = match_rooms(segments, truth);
  return out;
}

}  // namespace tsgraphs::eval
