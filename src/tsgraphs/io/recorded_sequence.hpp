#pragma once
/// A bag as a sequence, whatever its format (ROS 1, rosbag2): what is asked of it (BagOptions),
/// what it gives (RecordedSequence), and what every reader does with its messages once decoded
/// (place_scans: the scans in stamp order, each placed by the base's odometry interpolated to
/// its stamp and the sensor's mount). No ROS type here.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "tsgraphs/core/pose.hpp"
#include "tsgraphs/io/scan_sequence.hpp"

namespace tsgraphs::io {

/// What to read from a bag (ROS 1 or rosbag2).
struct BagOptions {
  std::string bag;           ///< the .bag file, or the rosbag2 folder, .db3 or .mcap file
  std::string points_topic;  ///< sensor_msgs/PointCloud2
  std::string odom_topic;    ///< nav_msgs/Odometry or geometry_msgs/PoseStamped: the base in a fixed frame
  std::string odom_tum;      ///< or a TUM file of the same (used when odom_topic is empty); with
                             ///< neither, the scans come without odometry (run estimates it)
  /// T_base_sensor; when empty, the /tf_static transform whose child is the clouds' frame (one
  /// hop), else identity.
  std::optional<Pose3> sensor_to_base;
};

struct StampedBase;

/// A bag's scans placed by its odometry, whatever the bag's format (BagSequence for ROS 1,
/// Rosbag2Sequence for rosbag2): what `run` and `convert` ask of either. Scans outside the
/// odometry's time span are left out (dropped_scans() counts them).
class RecordedSequence : public ScanSequence {
 public:
  std::size_t size() const override { return info_.times.size(); }
  const SequenceInfo& info() const override { return info_; }
  const std::string& dir() const override { return name_; }
  std::size_t dropped_scans() const { return dropped_; }
  /// What the reader noted while opening (rosbag's own lines, an MCAP index not used), for
  /// the front end to print.
  const std::vector<std::string>& warnings() const { return warnings_; }
  /// The sensor-to-base transform used.
  const Pose3& sensor_to_base() const { return sensor_to_base_; }
  /// Whether it came from the options or /tf_static (else it is the identity by default).
  bool sensor_to_base_known() const { return sensor_to_base_known_; }

 protected:
  explicit RecordedSequence(std::string name) : name_(std::move(name)) {}
  /// The clouds stamped `stamps` placed by `odom` (place_scans) into info_ and dropped_; returns
  /// the indices of the clouds kept, in order. No cloud within the odometry's time span is an
  /// InputError naming the bag and the points topic.
  std::vector<std::size_t> place(const std::vector<double>& stamps, std::vector<StampedBase> odom,
                                 bool has_odometry, const std::string& points_topic);
  std::string name_;
  SequenceInfo info_;
  Pose3 sensor_to_base_ = Pose3::Identity();
  bool sensor_to_base_known_ = false;
  std::size_t dropped_ = 0;
  std::vector<std::string> warnings_;
};

/// The base's pose in a fixed frame at a stamp (s), as an odometry topic gives it.
struct StampedBase {
  double t = 0.0;
  Pose3 pose = Pose3::Identity();
};

/// Adds the TUM file's poses (options.odom_tum) when they stand for the odometry topic; odometry
/// asked for (a topic or a file) and none found is an InputError naming the bag.
void add_tum_odometry(const BagOptions& options, std::vector<StampedBase>& odom);

/// The pose at time t between two samples: position linear, rotation slerp.
Pose3 interpolate(const StampedBase& a, const StampedBase& b, double t);

struct ScanPlacement {
  std::vector<std::size_t> kept;  ///< indices into the clouds, in stamp order (file order among equal stamps)
  std::vector<double> times;      ///< their stamps
  std::vector<Pose3> odometry;    ///< the sensor's poses (empty without odometry)
  std::size_t dropped = 0;        ///< clouds outside the odometry's time span, left out
};

/// The clouds stamped `cloud_stamps` placed by `odom` (sorted here by stamp) times
/// `sensor_to_base`; without odometry (`has_odometry` false) they keep their stamps only.
ScanPlacement place_scans(const std::vector<double>& cloud_stamps, std::vector<StampedBase> odom,
                          bool has_odometry, const Pose3& sensor_to_base);

}  // namespace tsgraphs::io
