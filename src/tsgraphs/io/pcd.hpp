#pragma once
/// PCD files (v0.7: ascii, binary, binary_compressed), read and written without PCL.
#include <string>

#include "tsgraphs/core/point_cloud.hpp"

namespace tsgraphs::io {

/// Reads x y z (and intensity when the file has it). Points with a non-finite coordinate
/// are dropped (organised clouds carry NaNs for missing returns). A missing or malformed
/// file is an InputError naming it.
PointCloud read_pcd(const std::string& path);

/// The bytes of a binary PCD (v0.7) of the cloud: float x y z, and intensity when the cloud
/// has it; unorganised (HEIGHT 1). Written by hand (a header and the floats), so that a caller
/// can write it through write_file_atomic.
std::string encode_pcd(const PointCloud& cloud);

}  // namespace tsgraphs::io
