#include "segment_map.hpp"

#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <algorithm>
#include <array>

#include "output_checks.hpp"
#include "tsgraphs/core/error.hpp"
#include "tsgraphs/eval/label_metrics.hpp"
#include "tsgraphs/io/atomic_write.hpp"
#include "tsgraphs/io/image.hpp"
#include "tsgraphs/io/occupancy_map.hpp"
#include "tsgraphs/io/room_labels.hpp"
#include "tsgraphs/io/room_labels_writer.hpp"
#include "tsgraphs/pipeline/pipeline_config.hpp"
#include "tsgraphs/rooms/map_segmentation.hpp"

namespace tsgraphs::app {
namespace {

nlohmann::json figure(const std::optional<double>& x) {
  return x ? nlohmann::json(*x) : nlohmann::json(nullptr);
}

std::string percent(const std::optional<double>& x) {
  if (!x) return "-";
  char buf[16];
  std::snprintf(buf, sizeof buf, "%.1f", 100.0 * *x);
  return buf;
}

/// The map's rooms, by the parameters' room segmentation and map walls.
rooms::MapSegmentation segment(const io::OccupancyMap& map, const pipeline::PipelineConfig& params) {
  GridFrame frame;
  frame.resolution = map.meta.resolution;
  frame.cols = map.width;
  frame.rows = map.height;
  std::vector<std::uint8_t> free(frame.size()), occupied(frame.size());
  for (std::size_t i = 0; i < frame.size(); ++i) {
    free[i] = map.cells[i] == io::CellState::kFree ? 1 : 0;
    occupied[i] = map.cells[i] == io::CellState::kOccupied ? 1 : 0;
  }
  rooms::MapSegmentationConfig config;
  config.walls = params.map_walls;
  config.segmentation = params.rooms.segmentation;
  config.robot_radius = params.rooms.free_space.lambda_th;
  return rooms::segment_map(frame, free, occupied, config);
}

/// The figures against the true rooms into the metrics' JSON.
void add_figures(nlohmann::json& out, const eval::LabelFigures& figures, const io::RoomLabels& truth,
                 const std::string& truth_file) {
  out["truth"] = {
      {"file", truth_file}, {"rooms", truth.count}, {"convention", io::convention_name(truth.convention)}};
  out["ipa"] = {{"precision_micro", figure(figures.ipa.precision_micro)},
                {"recall_micro", figure(figures.ipa.recall_micro)},
                {"precision_macro", figure(figures.ipa.precision_macro)},
                {"recall_macro", figure(figures.ipa.recall_macro)}};
  out["room_match"] = {{"precision", figure(figures.rooms.precision)},
                       {"recall", figure(figures.rooms.recall)},
                       {"f1", figure(figures.rooms.f1)},
                       {"mean_iou", figure(figures.rooms.mean_iou)},
                       {"matched", figures.rooms.n_matched},
                       {"segments", figures.rooms.n_segments},
                       {"truth_rooms", figures.rooms.n_truth}};
}

}  // namespace

void segment_map(const SegmentMapOptions& options) {
  if (options.map.empty()) throw input_error("segment-map", 0, "give the map's YAML file");
  if (options.out.empty()) throw input_error("segment-map", 0, "give --out LABELS.png");
  std::vector<std::string> inputs = map_inputs(options.map);
  inputs.insert(inputs.end(), {options.rooms, options.config});
  check_output_apart("--out", options.out, inputs);
  check_output_apart("--metrics", options.metrics, inputs);
  const auto t0 = std::chrono::steady_clock::now();
  const pipeline::PipelineConfig params =
      options.config.empty() ? pipeline::PipelineConfig{} : pipeline::load_pipeline_config(options.config);
  const io::OccupancyMap map = io::read_occupancy_map(options.map);
  std::optional<io::RoomLabels> truth;
  if (!options.rooms.empty()) {
    truth = io::read_room_labels(options.rooms, map);
    for (const std::string& w : truth->warnings)
      std::fprintf(stderr, "tsgraphs: warning: %s: %s\n", options.rooms.c_str(), w.c_str());
  }

  const rooms::MapSegmentation seg = segment(map, params);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  nlohmann::json out = {{"map", options.map},
                        {"resolution", map.meta.resolution},
                        {"rooms", seg.rooms.spaces.size()},
                        {"seconds", seconds}};
  nlohmann::json walls = nlohmann::json::array();
  for (const rooms::WallCandidate& w : seg.walls)
    walls.push_back({w.end_a.x(), w.end_a.y(), w.end_b.x(), w.end_b.y()});
  out["walls"] = walls;  // [x0, y0, x1, y1] in the map frame (m from its lower-left corner)
  std::optional<eval::LabelFigures> figures;
  if (truth) {
    figures = eval::compare_labels(seg.rooms.label, truth->room, map.width);
    add_figures(out, *figures, *truth, options.rooms);
  }
  io::write_file_atomic(options.out,
                        io::encode_png(io::room_label_image(seg.rooms.label, map.width, map.height)));
  if (!options.metrics.empty()) {
    try {
      io::write_file_atomic(options.metrics, out.dump(2) + "\n");
    } catch (...) {
      std::remove(options.out.c_str());  // both outputs or neither
      throw;
    }
  }

  if (!options.quiet)
    std::printf("segment-map: %s: %d x %d cells at %.3f m; %zu walls, %zu rooms; %.1f s; wrote %s\n",
                options.map.c_str(), map.width, map.height, map.meta.resolution, seg.walls.size(),
                seg.rooms.spaces.size(), seconds, options.out.c_str());
  if (figures) {
    std::printf(
        "against %s (%d rooms): IPA precision / recall micro %s / %s %%, macro %s / %s %%; rooms at IoU 0.5: "
        "precision %s, recall %s, F1 %s %% (%d of %d segments, %d true rooms)\n",
        options.rooms.c_str(), truth->count, percent(figures->ipa.precision_micro).c_str(),
        percent(figures->ipa.recall_micro).c_str(), percent(figures->ipa.precision_macro).c_str(),
        percent(figures->ipa.recall_macro).c_str(), percent(figures->rooms.precision).c_str(),
        percent(figures->rooms.recall).c_str(), percent(figures->rooms.f1).c_str(), figures->rooms.n_matched,
        figures->rooms.n_segments, figures->rooms.n_truth);
  }
}

}  // namespace tsgraphs::app
