#include "tsgraphs/eval/run_evaluation.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/eval/footprint_raster.hpp"
#include "tsgraphs/eval/ipa_segmentation_metrics.hpp"
#include "tsgraphs/eval/room_metrics.hpp"
#include "tsgraphs/eval/room_support.hpp"
#include "tsgraphs/eval/trajectory_metrics.hpp"
#include "tsgraphs/io/run_folder.hpp"
#include "tsgraphs/io/sequence_folder.hpp"
#include "tsgraphs/io/tum.hpp"
#include "tsgraphs/scene/scene_loader.hpp"

namespace tsgraphs::eval {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t i = std::min(v.size() - 1, static_cast<std::size_t>(std::ceil(q * v.size())) - 1);
  return v[i];
}

double mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return v.empty() ? 0.0 : s / v.size();
}

// Front-end, ground and back-end figures from timings.csv.
void timing_figures(const io::Timings& timings, Metrics* m) {
  std::vector<double> frontend, pgo;
  long tp = 0, fp = 0, fn = 0;
  bool labelled = false;
  for (const io::ScanTiming& s : timings.scans) {
    frontend.push_back(s.frontend_ms);
    // Ground counts are -1 for scans without labels.
    if (s.ground_tp >= 0) {
      labelled = true;
      tp += s.ground_tp;
      fp += s.ground_fp;
      fn += s.ground_fn;
    }
  }
  for (const io::OptimizationTiming& o : timings.optimizations) pgo.push_back(o.seconds);
  if (!frontend.empty()) {
    m->speed.frontend_ms_mean = mean(frontend);
    m->speed.frontend_ms_p95 = percentile(frontend, 0.95);
  }
  if (labelled) {
    if (tp + fp > 0) m->ground.precision = static_cast<double>(tp) / (tp + fp);
    if (tp + fn > 0) m->ground.recall = static_cast<double>(tp) / (tp + fn);
    if (m->ground.precision && m->ground.recall && *m->ground.precision + *m->ground.recall > 0)
      m->ground.f1 =
          2 * *m->ground.precision * *m->ground.recall / (*m->ground.precision + *m->ground.recall);
  }
  double total = 0;
  for (double t : pgo) total += t;
  m->pgo.t_pgo_s = total;
  m->pgo.n_optimisations = static_cast<double>(pgo.size());
  if (!pgo.empty()) {
    m->pgo.t_pgo_mean_s = mean(pgo);
    m->pgo.t_pgo_p95_s = percentile(pgo, 0.95);
    m->pgo.n_variables = timings.optimizations.back().n_variables;
    m->pgo.n_factors = timings.optimizations.back().n_factors;
  }
}

std::vector<Pose3> poses_of(const std::vector<io::StampedPose>& stamped) {
  std::vector<Pose3> out;
  out.reserve(stamped.size());
  for (const auto& s : stamped) out.push_back(s.pose);
  return out;
}

/// A final room carried into the truth frame: its footprint and the height of its floor there.
struct TruthFrameRoom {
  OrientedRect rect;
  Polygon2 polygon;  ///< empty: rect
  double z = 0.0;
};

/// The rooms under T_truth_map; a room's floor is its level's height (0 for an unknown level).
std::vector<TruthFrameRoom> in_truth_frame(const std::vector<FinalRoom>& rooms,
                                           const std::vector<double>& level_heights, const Pose3& T) {
  std::vector<TruthFrameRoom> out;
  for (const auto& [rect, level, polygon] : rooms) {
    const double floor =
        level >= 0 && level < static_cast<int>(level_heights.size()) ? level_heights[level] : 0.0;
    const Eigen::Vector3d c = T * Eigen::Vector3d(rect.center.x(), rect.center.y(), floor);
    TruthFrameRoom r;
    r.rect = rect;
    r.rect.center = c.head<2>();
    r.rect.yaw = rect.yaw + std::atan2(T.linear()(1, 0), T.linear()(0, 0));
    for (const Vec2& p : polygon) r.polygon.push_back((T * Eigen::Vector3d(p.x(), p.y(), floor)).head<2>());
    r.z = c.z();
    out.push_back(r);
  }
  return out;
}

/// The name of the level whose height is nearest `z` (ties: the first); "" without levels.
std::string nearest_level(double z, const std::vector<std::string>& names,
                          const std::vector<double>& heights) {
  std::string name;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (std::abs(heights[i] - z) < best) {
      best = std::abs(heights[i] - z);
      name = names[i];
    }
  }
  return name;
}

/// The figures of the final rooms (truth frame) against the sequence's rooms_gt.json and
/// scene.yaml (either may be missing): room F1 and segmentation, IPA precision / recall, and
/// unsupported rooms, judged by the scene where there is one, else by the true rooms.
void truth_room_figures(const std::vector<TruthFrameRoom>& placed, const io::SequenceInfo& si,
                        const scene::Scene* scene, Metrics* m) {
  if (si.has_rooms) {
    // Each room on the true level nearest its floor.
    std::vector<std::string> names;
    std::vector<double> heights;
    for (const io::RoomTruth& t : si.rooms) {
      names.push_back(t.level);
      heights.push_back(t.elevation);
    }
    std::vector<DetectedRoom> detected;
    std::vector<LevelFootprint> footprints;
    for (const TruthFrameRoom& r : placed) {
      detected.push_back({r.rect, nearest_level(r.z, names, heights), r.polygon});
      footprints.push_back({detected.back().footprint(), detected.back().level});
    }
    const std::vector<io::RoomTruth> visited = visited_rooms(si.rooms, si.groundtruth);
    m->rooms_gt.n_truth = static_cast<double>(si.rooms.size());
    m->rooms_gt.n_truth_visited = static_cast<double>(visited.size());
    const RoomsVsTruth r = rooms_vs_truth(detected, visited);
    m->rooms_gt.precision = r.precision;
    m->rooms_gt.recall = r.recall;
    m->rooms_gt.f1 = r.f1;
    m->rooms_gt.mean_iou = r.mean_iou;
    m->rooms_gt.under_segmented = r.under_segmented;
    m->rooms_gt.over_segmented = r.over_segmented;
    m->rooms_gt.n_rooms_final = r.n_rooms_final;
    const IpaFigures ipa = ipa_segmentation_metrics(footprints, si.rooms, visited);
    m->rooms_gt.ipa_precision_micro = ipa.precision_micro;
    m->rooms_gt.ipa_recall_micro = ipa.recall_micro;
    m->rooms_gt.ipa_precision_macro = ipa.precision_macro;
    m->rooms_gt.ipa_recall_macro = ipa.recall_macro;
    if (scene == nullptr) {
      const RoomSupport support = room_support(unwalkable_shares(footprints, si.rooms));
      m->rooms_gt.unsupported = support.unsupported;
      m->rooms_gt.unsupported_fraction_max = support.max_unwalkable_share;
    }
  }
  if (scene != nullptr) {
    // Walkability from the building itself: each room on the scene's level nearest its floor.
    std::vector<std::string> names;
    std::vector<double> heights;
    for (const scene::Level& l : scene->levels) {
      names.push_back(l.name);
      heights.push_back(l.elevation);
    }
    std::vector<LevelFootprint> footprints;
    for (const TruthFrameRoom& r : placed)
      footprints.push_back({footprint_of(r.rect, r.polygon), nearest_level(r.z, names, heights)});
    const RoomSupport support = room_support(unwalkable_shares(footprints, *scene));
    m->rooms_gt.unsupported = support.unsupported;
    m->rooms_gt.unsupported_fraction_max = support.max_unwalkable_share;
  }
}

/// The room map's footprints of a scene graph (map frame).
std::vector<FinalRoom> final_rooms_of(const io::SceneGraph& graph) {
  std::vector<FinalRoom> rooms;
  for (const io::SceneGraph::Room& r : graph.rooms) rooms.push_back({r.rect, r.level, r.polygon});
  return rooms;
}

/// The keyframes of a scene graph: the scan each was made from and its pose (map frame).
struct Keyframes {
  std::vector<std::size_t> scans;
  std::vector<Pose3> poses;
};

Keyframes keyframes_of(const io::SceneGraph& graph) {
  Keyframes out;
  for (const io::SceneGraph::Keyframe& k : graph.keyframes) {
    out.scans.push_back(k.scan_index);
    out.poses.push_back(k.pose.pose());
  }
  return out;
}

/// The scene graph's wall planes that have a segment and a height range.
std::vector<MappedWall> mapped_walls(const io::SceneGraph& graph) {
  std::vector<MappedWall> walls;
  for (const io::SceneGraph::Plane& p : graph.planes) {
    if (p.kind != "wall" || !p.segment || !p.z_range) continue;
    MappedWall w;
    w.id = p.id;
    w.plane.n = p.n;
    w.plane.d = p.d;
    w.a = (*p.segment)[0];
    w.b = (*p.segment)[1];
    w.z0 = (*p.z_range)[0];
    w.z1 = (*p.z_range)[1];
    walls.push_back(w);
  }
  return walls;
}

/// Loop closures: the keyframes each joins, its measured relative pose, whether a room proposed it.
struct AcceptedLoops {
  std::vector<std::pair<int, int>> keyframes;
  std::vector<Pose3> measurements;
  std::vector<bool> by_room;
};

/// Loops as accepted (the graph's edges may have moved since: keyframe retirement folds them);
/// run folders from before the list existed: the graph's loop edges.
AcceptedLoops accepted_loops(const io::SceneGraph& graph) {
  AcceptedLoops loops;
  if (!graph.loop_closures.empty() || graph.loop_edges.empty()) {
    for (const io::SceneGraph::LoopClosure& l : graph.loop_closures) {
      loops.keyframes.emplace_back(l.from, l.to);
      loops.measurements.push_back(l.measurement.pose());
      loops.by_room.push_back(l.proposer == "room");
    }
  } else {
    for (const io::SceneGraph::LoopEdge& e : graph.loop_edges) {
      loops.keyframes.emplace_back(e.from, e.to);
      loops.measurements.push_back(e.measurement.pose());
      loops.by_room.push_back(false);
    }
  }
  return loops;
}

/// The two-lap consistency from the room events, when the run has them.
void consistency_figures(const std::string& events_file, Metrics* m) {
  if (!fs::exists(events_file)) return;
  const Consistency c = consistency(io::read_room_events(events_file));
  m->consistency.N1st = c.N1st;
  m->consistency.N2nd = c.N2nd;
  m->consistency.N_re = c.N_re;
  m->consistency.f_re = c.f_re;
  if (c.dcs) m->consistency.dcs = *c.dcs;
  if (c.d_center) m->consistency.d_center = *c.d_center;
}

/// Every keyframe's scan is indexed later (its true pose, its scan): all checked here.
void check_keyframe_scans(const std::vector<std::size_t>& scans, const io::SequenceInfo& si,
                          const std::string& graph_file) {
  for (std::size_t k = 0; k < scans.size(); ++k) {
    if (scans[k] >= si.odometry.size() || (!si.groundtruth.empty() && scans[k] >= si.groundtruth.size()))
      throw input_error(graph_file, 0,
                        "'keyframes[" + std::to_string(k) + "].scan_index' is " + std::to_string(scans[k]) +
                            ": beyond the sequence's " + std::to_string(si.odometry.size()) + " scans");
  }
}

/// A room the raster would refuse is the run's fault, not the ground truth's: an InputError
/// naming the scene graph.
void check_room_sizes(const std::vector<TruthFrameRoom>& placed, const std::string& graph_file) {
  for (std::size_t i = 0; i < placed.size(); ++i) {
    if (placed[i].rect.area() > kMaxRasterCells * kRasterCell * kRasterCell)
      throw input_error(graph_file, 0,
                        "'rooms[" + std::to_string(i) + "].rect.size' is too large for a room");
    if (placed[i].polygon.empty()) continue;
    double y_min = placed[i].polygon[0].y(), y_max = y_min;
    for (const Vec2& p : placed[i].polygon) y_min = std::min(y_min, p.y()), y_max = std::max(y_max, p.y());
    if (area(placed[i].polygon) > kMaxRasterCells * kRasterCell * kRasterCell ||
        (y_max - y_min) / kRasterCell + 1 > kMaxRasterCells)
      throw input_error(graph_file, 0, "'rooms[" + std::to_string(i) + "].polygon' is too large for a room");
  }
}

/// The odometry the run started from against the truth: its own odometry.txt (LiDAR odometry,
/// or a copy of the input's), or the sequence's for run folders written before it existed.
void odometry_figures(const std::string& dir, const io::SequenceInfo& si, Metrics* m) {
  const std::string odometry_file = dir + "/odometry.txt";
  const std::vector<Pose3> odometry =
      fs::exists(odometry_file) ? poses_of(io::read_tum(odometry_file)) : si.odometry;
  if (odometry.size() != si.groundtruth.size())
    throw input_error(odometry_file, 0,
                      std::to_string(odometry.size()) + " poses but the sequence has " +
                          std::to_string(si.groundtruth.size()) + " scans");
  m->trajectory.odom_ate_rmse = ate_rmse(odometry, si.groundtruth);
}

/// Loop closures against the true relative poses of their keyframes.
void loop_figures(const AcceptedLoops& loops, const std::vector<std::size_t>& kf_scan,
                  const io::SequenceInfo& si, const EvalOptions& options, const std::string& graph_file,
                  Metrics* m) {
  double max_err_m = 0, max_err_deg = 0;
  int correct = 0, room_correct = 0;
  for (std::size_t i = 0; i < loops.keyframes.size(); ++i) {
    const auto [from, to] = loops.keyframes[i];
    if (from < 0 || to < 0 || static_cast<std::size_t>(std::max(from, to)) >= kf_scan.size())
      throw input_error(graph_file, 0, "loop edge names an unknown keyframe");
    const Pose3 truth = si.groundtruth[kf_scan[from]].inverse() * si.groundtruth[kf_scan[to]];
    const Pose3 err = truth.inverse() * loops.measurements[i];
    const double em = err.translation().norm();
    const double ed = Eigen::AngleAxisd(err.linear()).angle() * 180.0 / M_PI;
    max_err_m = std::max(max_err_m, em);
    max_err_deg = std::max(max_err_deg, ed);
    if (em <= options.loop_tolerance_m && ed <= options.loop_tolerance_deg) {
      ++correct;
      room_correct += loops.by_room[i] ? 1 : 0;
    }
  }
  m->loops.n_loops_correct = correct;
  m->loops.n_loops_room_correct = room_correct;
  if (!loops.keyframes.empty()) {
    m->loops.max_loop_err_m = max_err_m;
    m->loops.max_loop_err_deg = max_err_deg;
  }
}

/// Walls: faces seen from the keyframes (true poses, labelled points) against the mapped planes.
void wall_figures(const scene::Scene& scene, const io::SequenceReader& seq, const Keyframes& keyframes,
                  const std::vector<MappedWall>& walls, const WallMetricsConfig& config,
                  const std::string& graph_file, Metrics* m) {
  const io::SequenceInfo& si = seq.info();
  const std::vector<WallFaceTruth> faces = wall_faces(scene);
  std::vector<FaceHits> hits(faces.size());
  for (const std::size_t scan : keyframes.scans) {
    if (scan >= seq.size()) throw input_error(graph_file, 0, "keyframe scan index beyond the sequence");
    count_face_hits(faces, seq.scan(scan), si.groundtruth[scan], config, &hits);
  }
  const Pose3 T_world_map = si.groundtruth[keyframes.scans[0]] * keyframes.poses[0].inverse();
  const WallErrors we = wall_errors(faces, hits, walls, T_world_map, config);
  m->walls.n_faces_seen = we.n_faces_seen;
  m->walls.n_faces_mapped = we.n_faces_mapped;
  m->walls.n_duplicates = we.n_duplicates;
  if (we.n_faces_mapped > 0) {
    m->walls.mean_dist_err = we.mean_dist_err;
    m->walls.max_dist_err = we.max_dist_err;
    m->walls.mean_angle_err_deg = we.mean_angle_err_deg;
    m->walls.max_angle_err_deg = we.max_angle_err_deg;
  }
}

}  // namespace

std::vector<FinalRoom> read_final_rooms(const std::string& run_dir) {
  return final_rooms_of(io::read_scene_graph(run_dir + "/" + io::run_files::kSceneGraph));
}

Consistency compare_runs(const std::string& run_a, const std::string& run_b) {
  const auto detected = [](const std::string& dir) {
    if (!fs::is_directory(dir)) throw input_error(dir, 0, "not a run folder");
    std::vector<DetectedRoom> out;
    for (const FinalRoom& r : read_final_rooms(dir))
      out.push_back({r.rect, std::to_string(r.level), r.polygon});
    return out;
  };
  return consistency_between(detected(run_a), detected(run_b));
}

std::string comparison_json(const Consistency& c, const std::string& run_a, const std::string& run_b) {
  const auto figure = [](const std::optional<double>& v) { return v ? json(*v) : json(nullptr); };
  json pairs = json::array();
  for (const RoomPair& p : c.pairs)
    pairs.push_back({{"a", p.a}, {"b", p.b}, {"dice", p.dice}, {"center_distance", p.center_distance}});
  const json doc = {
      {"run", run_a},   {"against", run_b}, {"N_a", c.N1st},        {"N_b", c.N2nd},
      {"N_re", c.N_re}, {"f_re", c.f_re},   {"dcs", figure(c.dcs)}, {"d_center", figure(c.d_center)},
      {"pairs", pairs}};
  return doc.dump(2) + "\n";
}

Metrics evaluate_run(const EvalOptions& options) {
  Metrics m;
  const std::string dir = options.run_dir;
  if (!fs::is_directory(dir)) throw input_error(dir, 0, "not a run folder");
  const std::vector<Pose3> estimate = poses_of(io::read_tum(dir + "/" + io::run_files::kTrajectory));
  m.trajectory.ate_loop = ate_loop(estimate);
  timing_figures(io::read_timings(dir + "/" + io::run_files::kTimings), &m);
  const io::RunSummary info = io::read_run_summary(dir + "/" + io::run_files::kRunInfo);
  m.speed.rtf = info.rtf;
  m.speed.peak_rss_mb = info.peak_rss_mb;

  const std::string graph_file = dir + "/" + io::run_files::kSceneGraph;
  const io::SceneGraph graph = io::read_scene_graph(graph_file);
  const Keyframes keyframes = keyframes_of(graph);
  const std::vector<MappedWall> walls = mapped_walls(graph);
  const AcceptedLoops loops = accepted_loops(graph);
  m.loops.n_loops = static_cast<double>(loops.keyframes.size());
  m.loops.n_loops_room = static_cast<double>(std::count(loops.by_room.begin(), loops.by_room.end(), true));
  // Rooms: the two-lap consistency from the events; the final rooms for the ground truth.
  consistency_figures(dir + "/" + io::run_files::kRoomEvents, &m);
  const std::vector<FinalRoom> final_rooms = final_rooms_of(graph);

  if (options.seq_dir.empty()) return m;
  const io::SequenceReader seq(options.seq_dir);
  const io::SequenceInfo& si = seq.info();
  if (si.odometry.size() != estimate.size())
    throw input_error(dir + "/trajectory.txt", 0,
                      std::to_string(estimate.size()) + " poses but the sequence has " +
                          std::to_string(si.odometry.size()) + " scans: not a run of " + options.seq_dir);
  const std::string scene_file = seq.scene_path();
  const std::optional<scene::Scene> scene =
      scene_file.empty() ? std::nullopt : std::optional<scene::Scene>(scene::load_scene(scene_file));
  check_keyframe_scans(keyframes.scans, si, graph_file);
  if (!keyframes.poses.empty() && !si.groundtruth.empty() && (si.has_rooms || scene)) {
    const std::vector<TruthFrameRoom> placed = in_truth_frame(
        final_rooms, graph.levels, si.groundtruth[keyframes.scans.at(0)] * keyframes.poses[0].inverse());
    check_room_sizes(placed, graph_file);
    try {
      truth_room_figures(placed, si, scene ? &*scene : nullptr, &m);
    } catch (const std::invalid_argument& e) {  // a ground-truth polygon too large to rasterise
      throw input_error(options.seq_dir, 0, std::string("ground truth: ") + e.what());
    }
  }
  if (si.groundtruth.empty()) return m;
  m.trajectory.ate_rmse = ate_rmse(estimate, si.groundtruth);
  odometry_figures(dir, si, &m);
  loop_figures(loops, keyframes.scans, si, options, graph_file, &m);
  if (!scene || keyframes.scans.empty()) return m;
  wall_figures(*scene, seq, keyframes, walls, options.walls, graph_file, &m);
  return m;
}

}  // namespace tsgraphs::eval
