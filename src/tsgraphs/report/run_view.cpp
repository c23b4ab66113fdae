// Reading a run folder for the report: the scene graph's walls, nodes, rooms and levels, the
// trajectory, the timings, and the sequence's ground truth. Trajectories and room events
// are read with the io / eval readers; the scene graph and timings.csv here, because the
// report needs other parts of them than eval does (free space, times of each row).
#include "tsgraphs/report/run_view.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <utility>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/eval/room_metrics.hpp"
#include "tsgraphs/io/tum.hpp"
#include "tsgraphs/scene/scene_loader.hpp"

namespace tsgraphs::report {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw input_error(path, 0, "cannot open (is this a run folder written by `tsgraphs run`?)");
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

json parse_json(const std::string& text, const std::string& path) {
  try {
    return json::parse(text);
  } catch (const json::exception& e) {
    throw input_error(path, 0, std::string("malformed JSON: ") + e.what());
  }
}

Eigen::Vector3d vec3(const json& j) {
  const auto v = j.get<std::vector<double>>();
  if (v.size() != 3) throw std::out_of_range("expected [x, y, z]");
  return {v[0], v[1], v[2]};
}

Vec2 vec2(const json& j) {
  const auto v = j.get<std::vector<double>>();
  if (v.size() < 2) throw std::out_of_range("expected [x, y]");
  return {v[0], v[1]};
}

/// Walls, nodes, rooms (without first_lap) and levels of scene_graph.json.
void read_scene_graph(const std::string& path, RunView* run) {
  const json graph = parse_json(read_text(path), path);
  std::string part = "planes";  // names the list in the message
  try {
    for (const json& p : graph.at("planes")) {
      if (p.at("kind") != "wall" || !p.contains("segment") || !p.contains("z_range")) continue;
      RunView::Wall w;
      w.id = p.at("id").get<int>();
      const json& seg = p.at("segment");
      w.a = vec2(seg.at(0));
      w.b = vec2(seg.at(1));
      const auto z = p.at("z_range").get<std::vector<double>>();
      w.z0 = z.at(0);
      w.z1 = z.at(1);
      run->walls.push_back(w);
    }
    part = "traversable_nodes";
    for (const json& n : graph.at("traversable_nodes")) run->nodes.push_back({vec3(n.at("position"))});
    part = "rooms";
    for (const json& r : graph.at("rooms")) {
      RunView::Room room;
      room.id = r.at("id").get<int>();
      room.kind = r.at("kind").get<std::string>();
      room.level = r.at("level").get<int>();
      room.rect.center = vec2(r.at("rect").at("center"));
      room.rect.size = vec2(r.at("rect").at("size"));
      room.rect.yaw = r.at("rect").at("yaw").get<double>();
      if (r.contains("free_space")) {
        for (const json& p : r.at("free_space")) room.free_space.push_back(vec3(p));
      }
      run->rooms.push_back(std::move(room));
    }
    part = "levels";
    if (graph.contains("levels")) run->levels = graph.at("levels").get<std::vector<double>>();
  } catch (const std::exception& e) {  // json::exception, or out_of_range from a short list
    throw input_error(path, 0, "malformed " + part + ": " + e.what());
  }
}

std::vector<RunView::Stamped> positions(const std::vector<io::StampedPose>& poses) {
  std::vector<RunView::Stamped> out;
  out.reserve(poses.size());
  for (const io::StampedPose& s : poses) out.push_back({s.t, s.pose.translation()});
  return out;
}

/// A whole field as a number; false for anything else (empty, trailing characters).
bool parse_double(const std::string& field, double* v) {
  const char* end = field.data() + field.size();
  const auto r = std::from_chars(field.data(), end, *v);
  return r.ec == std::errc() && r.ptr == end;
}

/// The scan and optimization rows of timings.csv; columns found by the header's names.
void read_timings(const std::string& path, RunView* run) {
  std::istringstream in(read_text(path));
  auto split = [](const std::string& line) {
    std::vector<std::string> cols;
    std::stringstream ss(line);
    std::string c;
    while (std::getline(ss, c, ',')) cols.push_back(c);
    if (!line.empty() && line.back() == ',') cols.emplace_back();  // a last empty column
    return cols;
  };
  std::string line;
  if (!std::getline(in, line)) throw input_error(path, 1, "empty: expected the header line");
  const std::vector<std::string> header = split(line);
  auto column = [&](const std::string& name) {
    const auto it = std::find(header.begin(), header.end(), name);
    if (it == header.end()) throw input_error(path, 1, "header has no column '" + name + "'");
    return static_cast<std::size_t>(it - header.begin());
  };
  if (header.empty() || header[0] != "kind") throw input_error(path, 1, "header must start with 'kind'");
  const std::size_t stamp = column("stamp"), frontend = column("frontend_ms");
  const std::size_t seconds = column("optimization_s"), full = column("full");
  int line_no = 1;
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    const std::vector<std::string> cols = split(line);
    auto number = [&](std::size_t i, const char* name) {
      double v = 0.0;
      if (i >= cols.size() || !parse_double(cols[i], &v) || !std::isfinite(v)) {
        throw input_error(path, line_no, std::string("malformed ") + name + " in a " + cols[0] + " row");
      }
      return v;
    };
    if (cols[0] == "scan") {
      run->scans.push_back({number(stamp, "stamp"), number(frontend, "frontend_ms")});
    } else if (cols[0] == "optimization") {
      const double f = number(full, "full");
      if (f != 0.0 && f != 1.0) throw input_error(path, line_no, "full must be 0 or 1");
      run->solves.push_back({number(stamp, "stamp"), number(seconds, "optimization_s"), f == 1.0});
    } else {
      throw input_error(path, line_no, "expected a scan or optimization row, got '" + cols[0] + "'");
    }
  }
}

}  // namespace

RunView read_run_view(const std::string& run_dir, const std::string& seq_dir) {
  if (!fs::is_directory(run_dir)) throw input_error(run_dir, 0, "not a run folder");
  const fs::path dir(run_dir);
  RunView run;
  run.label = (dir.has_filename() ? dir.filename() : dir.parent_path().filename()).string();
  read_scene_graph((dir / "scene_graph.json").string(), &run);
  run.estimated = positions(io::read_tum((dir / "trajectory.txt").string()));
  read_timings((dir / "timings.csv").string(), &run);

  const fs::path events = dir / "rooms_events.jsonl";
  if (fs::exists(events)) {
    std::map<int, int> first_lap;
    for (const eval::RoomEvent& e : eval::read_room_events(events.string())) {
      const auto [it, inserted] = first_lap.emplace(e.room_id, e.lap);
      if (!inserted) it->second = std::min(it->second, e.lap);
    }
    for (RunView::Room& r : run.rooms) {
      const auto it = first_lap.find(r.id);
      r.first_lap = it == first_lap.end() ? 0 : it->second;
    }
  }
  const fs::path metrics = dir / "metrics.json";
  if (fs::exists(metrics)) {
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
