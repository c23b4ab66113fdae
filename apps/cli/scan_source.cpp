#include "scan_source.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "cli_checks.hpp"
#include "commands.hpp"
#include "output_checks.hpp"
#include "tsgraphs/core/error.hpp"

namespace tsgraphs::app::cli {

namespace {

// Bounds of --sensor-to-base: a mount this far from the base, or a quaternion this short, is a typo.
constexpr double kMaxMountOffset = 100.0;  // m
constexpr double kMinQuaternionNorm = 1e-3;

/// --sensor-to-base as a pose, none when not given.
std::optional<Pose3> mount_of(const std::vector<double>& v) {
  if (v.empty()) return std::nullopt;
  const bool finite = std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
  if (!finite || Eigen::Vector3d(v[0], v[1], v[2]).norm() > kMaxMountOffset)
    throw input_error("--sensor-to-base", 0, "x y z must be finite and within 100 m of the base");
  if (!(Eigen::Vector4d(v[3], v[4], v[5], v[6]).norm() > kMinQuaternionNorm))
    throw input_error("--sensor-to-base", 0, "qx qy qz qw must be a rotation (a quaternion of norm about 1)");
  Pose3 mount = Pose3::Identity();
  mount.translation() = Eigen::Vector3d(v[0], v[1], v[2]);
  mount.linear() = Eigen::Quaterniond(v[6], v[3], v[4], v[5]).normalized().toRotationMatrix();
  return mount;
}

}  // namespace

void add_scan_source_options(CLI::App& cmd, ScanSourceOptions& opt, const std::string& out_help) {
  cmd.add_option("SEQ_DIR", opt.seq,
                 "sequence folder (docs/scene-format.md), or a folder of .pcd / KITTI .bin scans (with a "
                 "pose file, or none)");
  cmd.add_option("--scans", opt.folder.scans, "glob of scan files (.pcd or KITTI .bin) instead of SEQ_DIR");
  cmd.add_option("--poses", opt.folder.poses,
                 "pose file of the scans, one per scan (default: poses.txt or odom.txt beside them)");
  cmd.add_option("--pose-format", opt.folder.pose_format,
                 "tum, kitti (3x4 rows) or auto (by the field count)")
      ->check(CLI::IsMember({"tum", "kitti", "auto"}))
      ->capture_default_str();
  cmd.add_option("--times", opt.folder.times,
                 "times of the scans, one a line (default: times.txt beside them, or the TUM stamps)");
  // An hour between scans is no sweep rate: a typo (1e308 overflowed the scan stamps).
  cmd.add_option("--scan-period", opt.folder.scan_period, "s between scans when nothing gives their times")
      ->check(number_in(1e-6, 3600.0))
      ->capture_default_str();
  cmd.add_option("--bag", opt.bag.bag,
                 "a ROS1 bag or a rosbag2 recording (folder, .db3 or .mcap) instead of SEQ_DIR (see "
                 "bag-info for its topics)");
  cmd.add_option("--points-topic", opt.bag.points_topic, "bag: the sensor_msgs/PointCloud2 topic");
  cmd.add_option("--odom-topic", opt.bag.odom_topic,
                 "bag: the nav_msgs/Odometry or geometry_msgs/PoseStamped topic");
  cmd.add_option("--odom-tum", opt.bag.odom_tum, "bag: odometry of the base from a TUM file instead");
  cmd.add_option(
         "--sensor-to-base", opt.sensor_to_base,
         "x y z qx qy qz qw of the sensor in the base frame: a bag's (default: /tf_static, else identity), "
         "and the first pose of scans without poses (default: level with the floor under the first scan)")
      ->expected(7);
  cmd.add_option("--odometry", opt.odometry,
                 "auto: the input's poses, or LiDAR odometry from the scans when it has none; input; lidar")
      ->check(CLI::IsMember({"auto", "input", "lidar"}))
      ->capture_default_str();
  cmd.add_option("--config", opt.config, "parameter file (config/params.yaml lists every key)");
  cmd.add_option("--out", opt.out, out_help)->required();
}

ScanSource open_scan_source(ScanSourceOptions& opt, const std::string& command, bool quiet) {
  const int sources = int(!opt.seq.empty()) + int(!opt.folder.scans.empty()) + int(!opt.bag.bag.empty());
  if (sources != 1) throw input_error(command, 0, "give one of SEQ_DIR, --scans GLOB or --bag FILE");
  check_output_apart("--out", opt.out,
                     {opt.seq, opt.folder.scans, opt.folder.poses, opt.folder.times, opt.bag.bag,
                      opt.bag.odom_tum, opt.config});
  std::optional<Pose3> mount = mount_of(opt.sensor_to_base);
  ScanSource source;
  if (!opt.bag.bag.empty()) {
    opt.bag.sensor_to_base = mount;
    OpenedBag bag = open_bag(opt.bag, quiet);
    if (bag.mount) mount = bag.mount;
    source.sequence = std::move(bag.sequence);
  } else {
    opt.folder.folder = opt.seq;
    source.sequence = open_sequence(opt.folder);
    if (!opt.sensor_to_base.empty() && !source.sequence->info().odometry.empty())
      throw input_error(source.sequence->dir(), 0,
                        "has poses of the sensor: --sensor-to-base is for bags and for scans without poses");
  }
  source.config =
      opt.config.empty() ? pipeline::PipelineConfig{} : pipeline::load_pipeline_config(opt.config);
  source.odometry =
      choose_odometry(*source.sequence, opt.odometry, mount, source.config.floor_levelling, quiet);
  return source;
}

}  // namespace tsgraphs::app::cli
