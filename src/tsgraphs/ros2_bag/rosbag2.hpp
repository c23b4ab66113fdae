#pragma once
/// rosbag2 recordings without ROS 2: a bag folder (metadata.yaml and its files, split bags in
/// order), or one SQLite (.db3, through Debian's libsqlite3) or MCAP (mcap.hpp) file, told
/// apart by their content. Scans from a sensor_msgs/msg/PointCloud2 topic, odometry from a
/// nav_msgs/msg/Odometry or geometry_msgs/msg/PoseStamped topic (or a TUM file), the mount from
/// /tf_static: as BagSequence reads ROS 1 bags (recorded_sequence.hpp).
#include <memory>
#include <string>
#include <vector>

#include "tsgraphs/io/recorded_sequence.hpp"
#include "tsgraphs/mcap/mcap.hpp"
#include "tsgraphs/io/scan_sequence.hpp"

namespace tsgraphs::ros2_bag {

/// Whether `path` is a rosbag2 recording: a folder holding metadata.yaml, or a file that
/// starts as SQLite or MCAP files do.
bool is_rosbag2(const std::string& path);

/// The scans of a rosbag2 recording with their odometry. Scans are read when asked for
/// (thread-safe). Its warnings are what a storage noted while opening (an MCAP index not used,
/// so the file was read from the start), each naming its file.
class Rosbag2Sequence : public io::RecordedSequence {
 public:
  /// InputError naming the recording (and topic, message or record) for one that cannot be
  /// read, a topic that is missing, of another type or of another definition under the type's
  /// name, an odometry topic with no pose, or no scan within the odometry's time span.
  explicit Rosbag2Sequence(const io::BagOptions& options);
  ~Rosbag2Sequence() override;
  PointCloud scan(std::size_t index) const override;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// `tsgraphs bag-info` of a rosbag2 recording: its storage, then per topic its type, message
/// count and mean rate, one line each.
std::string rosbag2_info(const std::string& path);

enum class Rosbag2Storage { sqlite, mcap };

/// rosbag2's own compression, zstd, as `ros2 bag record --compression-mode file|message` writes
/// it: each storage file compressed whole (read by decompressing it to TMPDIR first), or each
/// message's data. Only a bag folder records it (metadata.yaml); MCAP's chunk compression is
/// another matter, and the two can be combined.
enum class Rosbag2Compression { none, file, message };

/// What a bag folder's metadata.yaml says of the recording: its storage files, in order, and
/// rosbag2's own compression of them.
struct Rosbag2Metadata {
  std::vector<std::string> files;  ///< paths of files in the folder, as listed
  std::vector<std::string> names;  ///< the same as metadata.yaml spells them (for messages)
  Rosbag2Compression compression = Rosbag2Compression::none;
};

/// Reads FOLDER/metadata.yaml (rosbag2_bagfile_information: relative_file_paths, and
/// compression_mode and compression_format when given). An InputError naming it, with the line
/// when there is one, for: not YAML; no list of files, or an empty one; an entry that is not a
/// file name, or not a file in the folder; a file listed twice, under any spelling (./a.db3 and
/// a.db3, a link to it); a compression other than rosbag2's zstd; a file whose first message
/// comes before the last of the file listed before it, by the times of the `files` section
/// (rosbag2 >= Humble; a bag folder's reader checks the files' own times as it opens them).
Rosbag2Metadata read_rosbag2_metadata(const std::string& folder);

/// Writes `sequence` as rosbag2 writes a recording: SQLite (rosbag2's Humble layout, the bag's
/// metadata in its metadata table) or MCAP (profile ros2, cdr messages, ros2msg schemas, chunks
/// compressed by `compression`, the bag's metadata in a "rosbag2" Metadata record), with the
/// topics write_bag writes to ROS 1 bags: /points, /odom, /tf_static and /groundtruth. A `path`
/// ending in .db3 or .mcap is that one file; any other is a bag folder: metadata.yaml and
/// NAME_0.db3 or NAME_0.mcap (NAME_0.db3.zstd or NAME_0.mcap.zstd under `bag_compression`
/// file). Written under a temporary name and renamed, so a failed write leaves nothing.
void write_rosbag2(const io::ScanSequence& sequence, const std::string& path, Rosbag2Storage storage,
                   mcap::Compression compression, const Pose3& sensor_to_base,
                   Rosbag2Compression bag_compression = Rosbag2Compression::none);

}  // namespace tsgraphs::ros2_bag
