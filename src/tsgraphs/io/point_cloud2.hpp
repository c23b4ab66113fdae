#pragma once
/// Decoding sensor_msgs/PointCloud2 data without ROS types: any field layout (x, y, z as
/// float32 or float64, at any offset, padding between fields or points, extra fields ignored,
/// organised or not); intensity and per-point times (point_time.hpp) taken when present; points
/// with a non-finite coordinate dropped.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "tsgraphs/core/point_cloud.hpp"

namespace tsgraphs::io {

/// sensor_msgs/PointField datatypes.
enum class FieldType : std::uint8_t {
  int8 = 1,
  uint8 = 2,
  int16 = 3,
  uint16 = 4,
  int32 = 5,
  uint32 = 6,
  float32 = 7,
  float64 = 8
};

struct PointField2 {
  std::string name;
  std::uint32_t offset = 0;  ///< bytes from the start of a point
  std::uint8_t datatype = 7;
  std::uint32_t count = 1;
};

/// The fields of a PointCloud2 message that say where the points are.
struct PointCloud2Layout {
  std::uint32_t height = 1, width = 0;
  std::uint32_t point_step = 0, row_step = 0;
  bool is_bigendian = false;
  std::vector<PointField2> fields;
};

/// The points of `data` (row_step x height bytes). A layout without x, y and z, with a
/// coordinate that is not float32 or float64, a field past point_step, two fields sharing a
/// byte, big-endian data or too little data is an InputError naming `where` (e.g. "run.bag:
/// /points, message 12") and the field.
PointCloud decode_point_cloud2(const PointCloud2Layout& layout, const std::uint8_t* data, std::size_t size,
                               const std::string& where);

/// A serialized sensor_msgs/PointCloud2 (the ROS1 wire format, as a bag stores it) taken
/// apart without allocating what its lengths claim: the points are data_size bytes at
/// data_offset of the message.
struct PointCloud2Message {
  double stamp = 0.0;  ///< header.stamp, seconds
  std::string frame_id;
  PointCloud2Layout layout;
  std::size_t data_offset = 0, data_size = 0;
};

/// Every length (frame_id, the field list, each field's name, data) is checked against the
/// `size` bytes of `bytes` before it is used: a message cut short or claiming more than it
/// holds is an InputError naming `where` and the byte offset in the message.
PointCloud2Message parse_point_cloud2_message(const std::uint8_t* bytes, std::size_t size,
                                              const std::string& where);

}  // namespace tsgraphs::io
