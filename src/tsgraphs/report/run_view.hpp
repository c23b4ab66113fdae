#pragma once
/// What a run report draws: the parts of a run folder (docs/run.md, "Outputs") and of the
/// sequence folder it ran on that the pictures need, in the map frame. For simulated
/// sequences the map frame (the odometry frame at the first keyframe) is the scene's world
/// frame, so ground truth and scene overlay the run without a transform.
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "tsgraphs/core/rect.hpp"
#include "tsgraphs/io/sequence_folder.hpp"
#include "tsgraphs/scene/scene.hpp"

namespace tsgraphs::report {

struct RunView {
  std::string label;  ///< e.g. "TS-graphs"; read_run_view sets the run folder's name

  /// A mapped wall plane (scene_graph.json "planes" of kind wall): its segment in x, y and
  /// the heights its points span.
  struct Wall {
    int id = 0;
    Vec2 a = Vec2::Zero(), b = Vec2::Zero();
    double z0 = 0.0, z1 = 0.0;
  };
  /// A traversable node (scene_graph.json "traversable_nodes"[].position).
  struct Node {
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
  };
  /// A footprint of the room map (scene_graph.json "rooms").
  struct Room {
    int id = 0;
    std::string kind = "room";  ///< "room" or "corridor"
    int level = 0;              ///< index into `levels`
    OrientedRect rect;
    Polygon2 polygon;                         ///< the footprint when it is no rectangle (empty: rect)
    int first_lap = 0;                        ///< lowest lap of its rooms_events.jsonl lines; 0 without one
    std::vector<Eigen::Vector3d> free_space;  ///< vertices of its latest extraction

    Polygon2 footprint() const { return footprint_of(rect, polygon); }
    Vec2 center() const { return polygon.size() >= 3 ? centroid(polygon) : rect.center; }
  };
  struct Stamped {
    double t = 0.0;
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
  };
  /// A timings.csv scan row: when, and the front-end's time for it.
  struct ScanTime {
    double t = 0.0, frontend_ms = 0.0;
  };
  /// A timings.csv optimization row: when, its wall time, full or local.
  struct Solve {
    double t = 0.0, seconds = 0.0;
    bool full = false;
  };

  std::vector<Wall> walls;
  std::vector<Node> nodes;
  std::vector<Room> rooms;
  std::vector<double> levels;              ///< floor height of each level index (scene_graph.json)
  std::vector<Stamped> estimated;          ///< trajectory.txt
  std::vector<Stamped> truth;              ///< SEQ/groundtruth.txt; empty without it
  std::vector<io::RoomTruth> truth_rooms;  ///< SEQ/rooms_gt.json; empty without it
  std::optional<scene::Scene> scene;       ///< SEQ/scene.yaml (simulated sequences)
  std::vector<ScanTime> scans;
  std::vector<Solve> solves;
  std::string metrics_json;  ///< RUN/metrics.json text, "" without it
};

/// Reads `run_dir` (scene_graph.json, trajectory.txt and timings.csv required;
/// rooms_events.jsonl and metrics.json optional) and, when `seq_dir` is not empty, the
/// sequence folder it ran on. A missing required file or a malformed file is an InputError
/// naming the file (and the line, for text files). `read_metrics` false leaves metrics.json
/// unread (eval, about to replace it).
RunView read_run_view(const std::string& run_dir, const std::string& seq_dir = "", bool read_metrics = true);

/// A point is on a level when it is at most this far below the level's floor (a floor
/// point's noise, a wall plane starting under the slab)...
constexpr double kLevelBelowFloorM = 0.5;
/// ...and at most this far above it (the sensor, the free space, the walls of the storey).
constexpr double kLevelAboveFloorM = 3.0;

/// Index of the level a height belongs to: the highest floor at most kLevelBelowFloorM
/// above `z`, if `z` is at most kLevelAboveFloorM above that floor; -1 for none (e.g. a
/// storey the run never walked). A run without levels has everything on level 0.
int level_of_height(const RunView& run, double z);

/// The levels the estimated trajectory walks or that hold a room, lowest index first; {0}
/// when there is neither.
std::vector<int> visited_levels(const RunView& run);

/// The visited level with the most estimated poses (ties: the lower index).
int main_level(const RunView& run);

}  // namespace tsgraphs::report
