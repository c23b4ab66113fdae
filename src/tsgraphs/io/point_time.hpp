#pragma once
/// Per-point time fields as LiDAR drivers write them, read the same way from PCD files and
/// PointCloud2 messages: Ouster's `t` (uint32 nanoseconds from the scan's start), Velodyne's
/// `time` (float32 seconds from the message's stamp, often negative: the stamp is the sweep's
/// end), Hesai's and Livox's `timestamp` (float64 seconds, absolute or relative), Livox's
/// `offset_time` (uint32 nanoseconds).
#include <optional>
#include <string>
#include <vector>

namespace tsgraphs::io {

/// The names above, in the order a field is chosen when a cloud has several.
const std::vector<std::string>& time_field_names();

/// What one of a field's values is in seconds: integer fields hold nanoseconds, floating ones
/// seconds. None when `name` is not a time field.
std::optional<double> time_field_scale(const std::string& name, bool integer_type);

/// Times in seconds made relative to the scan: absolute ones (more than a day from 0, clock
/// time) are taken from the earliest point's, relative ones are kept as they are.
std::vector<float> relative_times(const std::vector<double>& seconds);

}  // namespace tsgraphs::io
