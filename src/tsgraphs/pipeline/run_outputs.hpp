#pragma once
/// What `tsgraphs run` writes into its output folder (docs/run.md): the trajectory of every
/// scan and the odometry it started from (TUM), the scene graph (JSON), the map (PLY, coloured by layer), the timings
/// (CSV), the parameters actually used and a run summary.
#include <string>

#include "tsgraphs/pipeline/pipeline.hpp"

namespace tsgraphs::pipeline {

/// Facts about the run that the pipeline does not know.
struct RunInfo {
  std::string sequence;          ///< input folder or file
  double sequence_duration_s = 0;///< last stamp - first stamp (+ one scan period)
  double wall_time_s = 0;        ///< whole run, reading included
  double peak_rss_mb = 0;
  std::size_t num_scans = 0;
  std::size_t num_skipped = 0;   ///< scans with a warning
  std::vector<double> lap_starts;///< the sequence's laps.txt (empty: laps found from the trajectory)
  bool estimated_odometry = false;///< the poses came from LiDAR odometry, not the input
};

/// File names inside a run folder.
namespace run_files {
inline constexpr const char* kTrajectory = "trajectory.txt";
inline constexpr const char* kOdometry = "odometry.txt";
inline constexpr const char* kSceneGraph = "scene_graph.json";
inline constexpr const char* kMap = "map.ply";
inline constexpr const char* kTimings = "timings.csv";
inline constexpr const char* kParams = "params.yaml";
inline constexpr const char* kRunInfo = "run_info.json";
inline constexpr const char* kMetrics = "metrics.json";
inline constexpr const char* kRoomEvents = "rooms_events.jsonl";
}  // namespace run_files

/// Where a mapped plane's points lie (map frame): their centroid projected on the plane, for a
/// wall the ends of their extent along it (x, y), and their height range.
struct PlaneExtent {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  Eigen::Vector2d a = Eigen::Vector2d::Zero(), b = Eigen::Vector2d::Zero();
  double z0 = 0, z1 = 0;
};
/// The extent of `points` (not empty) on `plane`.
PlaneExtent plane_extent(const Plane& plane, const std::vector<Eigen::Vector3f>& points);

/// Writes every output file of `pipeline` into the existing folder `dir`.
void write_run_outputs(const Pipeline& pipeline, const RunInfo& info, const std::string& dir);

/// The scene graph as JSON text (keyframes, planes, edges).
std::string scene_graph_json(const Pipeline& pipeline);
/// Lap (1, 2, ...) of each scan: from `lap_starts` when given, else a lap ends when the sensor
/// comes back within kLapRadius of its start after travelling more than kLapMinTravel
/// (docs/metrics.md).
std::vector<int> laps_of(const std::vector<double>& stamps, const std::vector<Pose3>& poses,
                         const std::vector<double>& lap_starts);
/// rooms_events.jsonl (docs/metrics.md): one JSON object per room extraction, in time order.
std::string room_events_jsonl(const Pipeline& pipeline, const std::vector<double>& lap_starts);
/// The timings table as CSV text: one row per scan, then one per optimisation.
std::string timings_csv(const Pipeline& pipeline);
/// Binary little-endian PLY of the map: keyframe points in grey, wall faces coloured per plane,
/// floors and ceilings in beige, traversable nodes in magenta.
std::string map_ply(const Pipeline& pipeline);

}  // namespace tsgraphs::pipeline
