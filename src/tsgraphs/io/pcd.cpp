#include "tsgraphs/io/pcd.hpp"

#include <pcl/PCLPointCloud2.h>
#include <pcl/console/print.h>
#include <pcl/conversions.h>
#include <pcl/io/pcd_io.h>
#include <pcl/point_types.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <vector>

#include "tsgraphs/core/error.hpp"

namespace tsgraphs::io {
namespace {

// PCL's reader can crash on a file that is not a PCD (PCL 1.13), so the header is checked
// here first: every key known, FIELDS / SIZE / TYPE / COUNT consistent, POINTS = WIDTH *
// HEIGHT, and a binary body long enough for POINTS points.
void check_pcd_header(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw input_error(path, 0, "cannot open file");
  std::map<std::string, std::vector<std::string>> keys;
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#') continue;
    std::istringstream s(line);
    std::string key;
    s >> key;
    static const std::set<std::string> kKnown = {"VERSION", "FIELDS", "SIZE", "TYPE", "COUNT",
                                                 "WIDTH", "HEIGHT", "VIEWPOINT", "POINTS", "DATA"};
    if (!kKnown.count(key)) throw input_error(path, line_no, "not a PCD header line: '" + line.substr(0, 40) + "'");
    std::vector<std::string> values;
    for (std::string v; s >> v;) values.push_back(v);
    keys[key] = values;
    if (key == "DATA") break;
  }
  for (const char* required : {"FIELDS", "SIZE", "TYPE", "WIDTH", "POINTS", "DATA"}) {
    if (!keys.count(required)) throw input_error(path, line_no, std::string("PCD header has no ") + required);
  }
  const std::size_t n_fields = keys["FIELDS"].size();
  if (n_fields == 0 || keys["SIZE"].size() != n_fields || keys["TYPE"].size() != n_fields ||
      (keys.count("COUNT") && keys["COUNT"].size() != n_fields)) {
    throw input_error(path, 0, "PCD header: FIELDS, SIZE, TYPE and COUNT disagree in length");
  }
  auto number = [&](const std::string& key) -> long long {
    try {
      if (keys[key].size() != 1) throw std::invalid_argument(key);
      return std::stoll(keys[key][0]);
    } catch (const std::exception&) {
      throw input_error(path, 0, "PCD header: " + key + " is not a number");
    }
  };
  const long long width = number("WIDTH");
  const long long height = keys.count("HEIGHT") ? number("HEIGHT") : 1;
  const long long points = number("POINTS");
  if (width < 0 || height < 0 || points != width * height) {
    throw input_error(path, 0, "PCD header: POINTS is not WIDTH * HEIGHT");
  }
  const std::string data = keys["DATA"].empty() ? "" : keys["DATA"][0];
  if (data != "ascii" && data != "binary" && data != "binary_compressed") {
    throw input_error(path, line_no, "PCD header: unknown DATA '" + data + "'");
  }
  long long point_bytes = 0;
  for (std::size_t i = 0; i < n_fields; ++i) {
    const long long size = std::stoll(keys["SIZE"][i]);
    const long long count = keys.count("COUNT") ? std::stoll(keys["COUNT"][i]) : 1;
    const std::string& type = keys["TYPE"][i];
    if ((size != 1 && size != 2 && size != 4 && size != 8) || (type != "F" && type != "I" && type != "U") || count < 1) {
      throw input_error(path, 0, "PCD header: bad SIZE/TYPE/COUNT for field " + keys["FIELDS"][i]);
    }
    point_bytes += size * count;
  }
  if (data == "binary") {
    const std::streamoff body = static_cast<std::streamoff>(in.tellg());
    const auto total = static_cast<long long>(std::filesystem::file_size(path));
    if (body < 0 || total - body < points * point_bytes) {
      throw input_error(path, 0, "PCD body is shorter than POINTS * point size (truncated file?)");
    }
  }
}

}  // namespace

PointCloud read_pcd(const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) throw input_error(path, 0, "no such file");
  check_pcd_header(path);
  pcl::console::setVerbosityLevel(pcl::console::L_ERROR);  // our own errors say what is wrong
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
