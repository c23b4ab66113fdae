#pragma once
/// PCD files (ASCII, binary, binary_compressed), read through PCL.
#include <string>

#include "tsgraphs/core/point_cloud.hpp"

namespace tsgraphs::io {

/// Reads x y z (and intensity when the file has it). Points with a non-finite coordinate
/// are dropped (organised clouds carry NaNs for missing returns). A missing or malformed
/// file is an InputError naming it.
PointCloud read_pcd(const std::string& path);

}  // namespace tsgraphs::io
