#pragma once
/// What `tsgraphs run` writes into its output folder (docs/run.md): the trajectory of every
/// scan and the odometry it started from (TUM), the scene graph (JSON), the map (PLY, coloured by layer), the
/// timings (CSV), the parameters actually used and a run summary. The files' schema is io/run_folder.hpp;
/// this fills it from a Pipeline.
#include <string>

#include "tsgraphs/io/run_folder.hpp"
#include "tsgraphs/pipeline/pipeline.hpp"

namespace tsgraphs::pipeline {

/// Facts about the run that the pipeline does not know.
struct RunInfo {
  std::string sequence;            ///< input folder or file
  double sequence_duration_s = 0;  ///< last stamp - first stamp (+ one scan period)
  double wall_time_s = 0;          ///< whole run, reading included
  double peak_rss_mb = 0;
  std::size_t num_scans = 0;
  std::size_t num_skipped = 0;        ///< scans with a warning
  std::vector<double> lap_starts;     ///< the sequence's laps.txt (empty: laps found from the trajectory)
  bool estimated_odometry = false;    ///< the poses came from LiDAR odometry, not the input
  std::size_t num_odometry_lost = 0;  ///< scans the LiDAR odometry reported lost (lidar_odometry.min_overlap)
  /// Where the pipeline's map frame is in the input's frame (run_sequence: map_origin_of); the
  /// pipeline holds everything relative to it, the files are written in the input's frame.
  Eigen::Vector3d map_origin = Eigen::Vector3d::Zero();
};

/// File names inside a run folder (io::run_files; the alias keeps the front ends' spelling).
namespace run_files = io::run_files;

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

/// Every node and edge of the pipeline's graph, its traversable nodes and its room map, moved
/// by `origin` (RunInfo::map_origin) into the input's frame.
io::SceneGraph scene_graph_of(const Pipeline& pipeline,
                              const Eigen::Vector3d& origin = Eigen::Vector3d::Zero());
/// scene_graph.json's text: format_scene_graph(scene_graph_of(pipeline, origin)).
std::string scene_graph_json(const Pipeline& pipeline,
                             const Eigen::Vector3d& origin = Eigen::Vector3d::Zero());
/// Lap (1, 2, ...) of each scan: from `lap_starts` when given, else a lap ends when the sensor
/// comes back within kLapRadius of its start after travelling more than kLapMinTravel
/// (docs/metrics.md).
std::vector<int> laps_of(const std::vector<double>& stamps, const std::vector<Pose3>& poses,
                         const std::vector<double>& lap_starts);
/// The room extractions in time order, each with its lap (laps_of), moved by `origin`.
std::vector<io::RoomEvent> room_events_of(const Pipeline& pipeline, const std::vector<double>& lap_starts,
                                          const Eigen::Vector3d& origin = Eigen::Vector3d::Zero());
/// rooms_events.jsonl (docs/metrics.md): one JSON object per room extraction, in time order.
std::string room_events_jsonl(const Pipeline& pipeline, const std::vector<double>& lap_starts,
                              const Eigen::Vector3d& origin = Eigen::Vector3d::Zero());
/// One row per scan, then one per optimisation.
io::Timings timings_of(const Pipeline& pipeline);
/// The timings table as CSV text.
std::string timings_csv(const Pipeline& pipeline);
/// run_info.json's figures: the pipeline's counts and `info`.
io::RunSummary run_summary_of(const Pipeline& pipeline, const RunInfo& info);
/// Binary little-endian PLY of the map, moved by `origin`: keyframe points in grey, wall faces
/// coloured per plane, floors and ceilings in beige, traversable nodes in magenta. Coordinates
/// are doubles: float32 holds UTM coordinates (4e6 m) only to 1/4 m.
std::string map_ply(const Pipeline& pipeline, const Eigen::Vector3d& origin = Eigen::Vector3d::Zero());

}  // namespace tsgraphs::pipeline
