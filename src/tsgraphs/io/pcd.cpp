#include "tsgraphs/io/pcd.hpp"

#include <pcl/PCLPointCloud2.h>
#include <pcl/conversions.h>
#include <pcl/io/pcd_io.h>
#include <pcl/point_types.h>

#include <cmath>
#include <filesystem>

#include "tsgraphs/core/error.hpp"

namespace tsgraphs::io {

PointCloud read_pcd(const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) throw input_error(path, 0, "no such file");
  pcl::PCLPointCloud2 blob;
  pcl::PCDReader reader;
  if (reader.read(path, blob) < 0) throw input_error(path, 0, "not a readable PCD file");
  bool has_x = false, has_intensity = false;
  for (const auto& f : blob.fields) {
    has_x = has_x || f.name == "x";
    has_intensity = has_intensity || f.name == "intensity";
  }
  if (!has_x) throw input_error(path, 0, "PCD has no x y z fields");
  PointCloud cloud;
  if (has_intensity) {
    pcl::PointCloud<pcl::PointXYZI> pts;
    pcl::fromPCLPointCloud2(blob, pts);
    cloud.reserve(pts.size(), true, false);
    for (const auto& p : pts) {
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) continue;
      cloud.points.emplace_back(p.x, p.y, p.z);
      cloud.intensity.push_back(std::isfinite(p.intensity) ? p.intensity : 0.0f);
    }
  } else {
    pcl::PointCloud<pcl::PointXYZ> pts;
    pcl::fromPCLPointCloud2(blob, pts);
    cloud.reserve(pts.size(), false, false);
    for (const auto& p : pts) {
      if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) cloud.points.emplace_back(p.x, p.y, p.z);
    }
  }
  return cloud;
}

}  // namespace tsgraphs::io
