// Reading a run folder for the report: the scene graph's walls, nodes, rooms and levels, the
// trajectory, the timings, and the sequence's ground truth, all through the io readers.
#include "tsgraphs/report/run_view.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <utility>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/core/text_file.hpp"
#include "tsgraphs/io/run_folder.hpp"
#include "tsgraphs/io/tum.hpp"
#include "tsgraphs/scene/scene_loader.hpp"

namespace tsgraphs::report {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string read_text(const std::string& path) {
  return read_text_file(path, "cannot open (is this a run folder written by `tsgraphs run`?)");
}

json parse_json(const std::string& text, const std::string& path) {
  try {
    return json::parse(text);
  } catch (const json::exception& e) {
    throw input_error(path, 0, std::string("malformed JSON: ") + e.what());
  }
}

/// Walls, nodes, rooms (without first_lap) and levels of scene_graph.json.
void take_scene_graph(const io::SceneGraph& graph, RunView* run) {
  for (const io::SceneGraph::Plane& p : graph.planes) {
    if (p.kind != "wall" || !p.segment || !p.z_range) continue;
    run->walls.push_back({p.id, (*p.segment)[0], (*p.segment)[1], (*p.z_range)[0], (*p.z_range)[1]});
  }
  for (const io::SceneGraph::TraversableNode& n : graph.traversable_nodes) run->nodes.push_back({n.position});
  for (const io::SceneGraph::Room& r : graph.rooms) {
    RunView::Room room;
    room.id = r.id;
    room.kind = r.kind;
    room.level = r.level;
    room.rect = r.rect;
    room.polygon = r.polygon;
    room.free_space = r.free_space;
    run->rooms.push_back(std::move(room));
  }
  run->levels = graph.levels;
}

std::vector<RunView::Stamped> positions(const std::vector<io::StampedPose>& poses) {
  std::vector<RunView::Stamped> out;
  out.reserve(poses.size());
  for (const io::StampedPose& s : poses) out.push_back({s.t, s.pose.translation()});
  return out;
}

/// The scan and optimization rows of timings.csv: when, and how long.
void take_timings(const io::Timings& timings, RunView* run) {
  for (const io::ScanTiming& s : timings.scans) run->scans.push_back({s.stamp, s.frontend_ms});
  for (const io::OptimizationTiming& o : timings.optimizations)
    run->solves.push_back({o.stamp, o.seconds, o.full});
}

}  // namespace

RunView read_run_view(const std::string& run_dir, const std::string& seq_dir, bool read_metrics) {
  if (!fs::is_directory(run_dir)) throw input_error(run_dir, 0, "not a run folder");
  const fs::path dir(run_dir);
  RunView run;
  run.label = (dir.has_filename() ? dir.filename() : dir.parent_path().filename()).string();
  take_scene_graph(io::read_scene_graph((dir / io::run_files::kSceneGraph).string()), &run);
  run.estimated = positions(io::read_tum((dir / io::run_files::kTrajectory).string()));
  take_timings(io::read_timings((dir / io::run_files::kTimings).string()), &run);

  const fs::path events = dir / io::run_files::kRoomEvents;
  if (fs::exists(events)) {
    std::map<int, int> first_lap;
    for (const io::RoomEvent& e : io::read_room_events(events.string())) {
      const auto [it, inserted] = first_lap.emplace(e.room_id, e.lap);
      if (!inserted) it->second = std::min(it->second, e.lap);
    }
    for (RunView::Room& r : run.rooms) {
      const auto it = first_lap.find(r.id);
      r.first_lap = it == first_lap.end() ? 0 : it->second;
    }
  }
  const fs::path metrics = dir / io::run_files::kMetrics;
  if (read_metrics && fs::exists(metrics)) {
    run.metrics_json = read_text(metrics.string());
    parse_json(run.metrics_json, metrics.string());  // refuse a malformed one here, not in the page
  }

  if (seq_dir.empty()) return run;
  // The sequence reader checks that its files agree; its ground truth has one pose per scan.
  const io::SequenceReader seq(seq_dir);
  const io::SequenceInfo& info = seq.info();
  for (std::size_t i = 0; i < info.groundtruth.size(); ++i) {
    run.truth.push_back({info.times[i], info.groundtruth[i].translation()});
  }
  run.truth_rooms = info.rooms;
  if (!seq.scene_path().empty()) run.scene = scene::load_scene(seq.scene_path());
  return run;
}

int level_of_height(const RunView& run, double z) {
  if (run.levels.empty()) return 0;
  int best = -1;
  for (std::size_t i = 0; i < run.levels.size(); ++i) {
    const double floor = run.levels[i];
    if (floor > z + kLevelBelowFloorM) continue;
    if (best < 0 || floor > run.levels[best]) best = static_cast<int>(i);
  }
  if (best >= 0 && z > run.levels[best] + kLevelAboveFloorM) return -1;
  return best;
}

std::vector<int> visited_levels(const RunView& run) {
  std::vector<bool> seen(std::max<std::size_t>(run.levels.size(), 1), false);
  for (const RunView::Stamped& s : run.estimated) {
    const int l = level_of_height(run, s.p.z());
    if (l >= 0) seen[l] = true;
  }
  for (const RunView::Room& r : run.rooms) {
    if (r.level >= 0 && r.level < static_cast<int>(seen.size())) seen[r.level] = true;
  }
  std::vector<int> out;
  for (std::size_t i = 0; i < seen.size(); ++i) {
    if (seen[i]) out.push_back(static_cast<int>(i));
  }
  if (out.empty()) out.push_back(0);
  return out;
}

int main_level(const RunView& run) {
  std::vector<std::size_t> poses(std::max<std::size_t>(run.levels.size(), 1), 0);
  for (const RunView::Stamped& s : run.estimated) {
    const int l = level_of_height(run, s.p.z());
    if (l >= 0) ++poses[l];
  }
  const std::vector<int> visited = visited_levels(run);
  int best = visited.front();
  for (int l : visited) {
    if (poses[l] > poses[best]) best = l;
  }
  return best;
}

}  // namespace tsgraphs::report
