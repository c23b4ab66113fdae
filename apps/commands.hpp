#pragma once
/// The commands of the `tsgraphs` program, each one call over the library; the demo chains them.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tsgraphs/eval/metrics.hpp"
#include "tsgraphs/eval/room_metrics.hpp"
#include "tsgraphs/ros1_bag/ros_bag.hpp"
#include "tsgraphs/ros2_bag/rosbag2.hpp"
#include "tsgraphs/io/scan_folder.hpp"
#include "tsgraphs/pipeline/pipeline_config.hpp"
#include "tsgraphs/pipeline/sequence_runner.hpp"
#include "tsgraphs/scene/scene.hpp"

namespace tsgraphs::app {

/// A scene file, or the name of a built-in scene (office, atrium, long_corridor, two_storeys).
scene::Scene resolve_scene(const std::string& arg);
/// resolve_scene, with the scene's warnings printed.
scene::Scene load_and_warn(const std::string& arg);
/// Warnings are shown even with --quiet: they say the output may not be what was meant.
void print_warnings(const std::string& where, const std::vector<std::string>& warnings);

/// `simulate`: the scene's sequence folder at `out` (laps <= 0: the scene's).
void simulate(const scene::Scene& scene, const std::string& out, std::uint64_t seed, int laps, bool quiet);
/// `simulate --bag`: the simulated sequence as a bag, through a sequence folder at `seq_dir`
/// (kept) or, when it is empty, a temporary one. `format`: ros1 (ros1_bag::write_bag), ros2-mcap or
/// ros2-sqlite (ros2_bag::write_rosbag2), or auto (by the file's extension: .bag, .mcap, .db3).
/// `compression`: "" for the format's default (ros1 lz4, ros2-mcap zstd, ros2-sqlite none),
/// else none, bz2 or lz4 for ros1, none, lz4 or zstd for ros2-mcap, none for ros2-sqlite.
void simulate_bag(const scene::Scene& scene, const std::string& bag, const std::string& seq_dir,
                  std::uint64_t seed, int laps, const std::string& format, const std::string& compression,
                  bool quiet);
/// `convert`: `sequence` (a folder of scans, a bag) written as a sequence folder at `out`:
/// scans/NNNNNN.bin, times.txt, odom.txt (and groundtruth.txt when it has ground truth). With
/// `odometry.estimate`, odom.txt is LiDAR odometry (`lidar`, its sweeps registered with `sweep`)
/// from the scans, in the same pass.
void convert(const io::ScanSequence& sequence, const std::string& out,
             const pipeline::OdometryOptions& odometry, const pipeline::PipelineConfig& config, bool quiet);
/// `bag-info`: the topics, types, counts and rates of a ROS 1 bag or a rosbag2 recording on stdout.
void print_bag_info(const std::string& bag);
/// `export --mcap`: the run folder as an MCAP file for Foxglove (report/foxglove_export.hpp).
void export_mcap(const std::string& run_dir, const std::string& out, bool quiet);
/// `draw-scene`: the bird's-eye SVG of the scene and its path.
void draw_scene(const scene::Scene& scene, const std::string& out, bool quiet);
/// What `run` reads: a sequence folder (docs/scene-format.md) when `options.folder` is one and
/// no scan glob is given, else a folder of PCD / KITTI scans with a pose file.
std::unique_ptr<io::ScanSequence> open_sequence(const io::ScanFolderOptions& options);
/// A bag opened for `run` and `convert`, and the sensor's mount when the bag (/tf_static) or
/// the options gave it.
struct OpenedBag {
  std::unique_ptr<io::ScanSequence> sequence;
  std::optional<Pose3> mount;
};
/// What `run --bag` reads: a ROS 1 bag or a rosbag2 recording (folder, .db3 or .mcap, told
/// apart by content), its scans with their odometry; says how many scans lay outside the
/// odometry's time span unless quiet.
OpenedBag open_bag(const io::BagOptions& options, bool quiet);
/// `--odometry`: where the poses come from. "input": the sequence's own (an InputError when it
/// has none); "lidar": LiDAR odometry from the scans; "auto": the input's when it has them,
/// else LiDAR odometry. Estimated poses start at the input's first pose when it has one, else
/// at `sensor_to_base` (the sensor's mount on a level base), else level with the floor under
/// the first scan (a warning when none is found: the first scan's frame, then).
pipeline::OdometryOptions choose_odometry(const io::ScanSequence& sequence, const std::string& mode,
                                          const std::optional<Pose3>& sensor_to_base,
                                          const odometry::FloorLevellingConfig& levelling, bool quiet);
/// `run`: a sequence through the pipeline into a run folder, written whole or not at all; with
/// `segmentations`, the room layer's segmentations as images in OUT/segmentations/.
void run(const io::ScanSequence& sequence, const std::string& out, const pipeline::PipelineConfig& config,
         bool quiet, const pipeline::OdometryOptions& odometry = {}, bool segmentations = false);
/// `run SEQ_DIR --out OUT` (the suite's and the demo's runs): the folder opened, checked and its
/// odometry chosen as the command does.
void run(const std::string& seq_dir, const std::string& out, const pipeline::PipelineConfig& config,
         bool quiet);
/// `eval`: metrics.json in the run folder (and the table on stdout when `print`).
eval::Metrics evaluate(const std::string& run_dir, const std::string& seq_dir, bool quiet, bool print = true);
/// `eval --against`: comparison.json in `run_a` (and the figures on stdout when `print`).
eval::Consistency compare(const std::string& run_a, const std::string& run_b, bool quiet, bool print = true);

}  // namespace tsgraphs::app
