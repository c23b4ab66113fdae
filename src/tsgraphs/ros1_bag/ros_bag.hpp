#pragma once
/// ROS1 bags (Debian's rosbag_storage; no ROS runtime): scans from a sensor_msgs/PointCloud2
/// topic with odometry from a nav_msgs/Odometry or geometry_msgs/PoseStamped topic (or a TUM
/// file), interpolated to the scan times; and a sequence written as a bag. No ROS type appears
/// in this header.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tsgraphs/io/recorded_sequence.hpp"
#include "tsgraphs/io/scan_sequence.hpp"

namespace tsgraphs::ros1_bag {

/// The scans of a ROS 1 bag with their odometry. Scans are read when asked for (thread-safe).
/// Its warnings are what rosbag itself said while the bag was opened (e.g. an index entry with
/// an invalid time: that message is not read), each "rosbag: ...".
class BagSequence : public io::RecordedSequence {
 public:
  /// InputError naming the bag (and topic) for a bag that cannot be read (missing, truncated),
  /// a topic that is missing or of another type, an odometry topic or file with no pose, or no
  /// scan inside the odometry's time span.
  explicit BagSequence(const io::BagOptions& options);
  ~BagSequence() override;
  PointCloud scan(std::size_t index) const override;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// `tsgraphs bag-info`: per topic its type, message count and mean rate, one line each.
std::string bag_info(const std::string& path);

enum class BagCompression { none, bz2, lz4 };

/// Writes `sequence` as a bag: /points (PointCloud2, float32 x y z intensity, frame "lidar"),
/// /odom (nav_msgs/Odometry "odom" -> "base_link": the odometry pose times sensor_to_base's
/// inverse), /tf_static ("base_link" -> "lidar" = sensor_to_base), and /groundtruth
/// (PoseStamped of the sensor) when the sequence has ground truth. Written under a temporary
/// name and renamed, so a failed write leaves nothing.
void write_bag(const io::ScanSequence& sequence, const std::string& path, BagCompression compression,
               const Pose3& sensor_to_base);

}  // namespace tsgraphs::ros1_bag
