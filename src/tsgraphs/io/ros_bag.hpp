#pragma once
/// ROS1 bags (Debian's rosbag_storage; no ROS runtime): scans from a sensor_msgs/PointCloud2
/// topic with odometry from a nav_msgs/Odometry or geometry_msgs/PoseStamped topic (or a TUM
/// file), interpolated to the scan times; and a sequence written as a bag. No ROS type appears
/// in this header.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tsgraphs/io/bag_placement.hpp"
#include "tsgraphs/io/scan_sequence.hpp"

namespace tsgraphs::io {

/// The scans of a bag with their odometry. Scans outside the odometry's time span are left
/// out (dropped_scans() counts them). Scans are read when asked for (thread-safe).
class BagSequence : public ScanSequence {
 public:
  /// InputError naming the bag (and topic) for a bag that cannot be read (missing, truncated),
  /// a topic that is missing or of another type, an odometry topic or file with no pose, or no
  /// scan inside the odometry's time span.
  explicit BagSequence(const BagOptions& options);
  ~BagSequence() override;
  std::size_t size() const override { return info_.times.size(); }
  const SequenceInfo& info() const override { return info_; }
  const std::string& dir() const override { return name_; }
  PointCloud scan(std::size_t index) const override;
  std::size_t dropped_scans() const { return dropped_; }
  /// What rosbag itself warned about while the bag was opened (e.g. an index entry with an
  /// invalid time: that message is not read), each "rosbag: ...", for the front end to print.
  const std::vector<std::string>& warnings() const { return warnings_; }
  /// The sensor-to-base transform used.
  const Pose3& sensor_to_base() const { return sensor_to_base_; }
  /// Whether it came from the options or /tf_static (else it is the identity by default).
  bool sensor_to_base_known() const { return sensor_to_base_known_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::string name_;
  SequenceInfo info_;
  Pose3 sensor_to_base_ = Pose3::Identity();
  bool sensor_to_base_known_ = false;
  std::size_t dropped_ = 0;
  std::vector<std::string> warnings_;
};

/// `tsgraphs bag-info`: per topic its type, message count and mean rate, one line each.
std::string bag_info(const std::string& path);

enum class BagCompression { none, bz2, lz4 };

/// Writes `sequence` as a bag: /points (PointCloud2, float32 x y z intensity, frame "lidar"),
/// /odom (nav_msgs/Odometry "odom" -> "base_link": the odometry pose times sensor_to_base's
/// inverse), /tf_static ("base_link" -> "lidar" = sensor_to_base), and /groundtruth
/// (PoseStamped of the sensor) when the sequence has ground truth. Written under a temporary
/// name and renamed, so a failed write leaves nothing.
void write_bag(const ScanSequence& sequence, const std::string& path, BagCompression compression,
               const Pose3& sensor_to_base);

}  // namespace tsgraphs::io
