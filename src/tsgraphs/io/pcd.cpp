#include "tsgraphs/io/pcd.hpp"

#include <pcl/PCLPointCloud2.h>
#include <pcl/console/print.h>
#include <pcl/conversions.h>
#include <pcl/io/pcd_io.h>
#include <pcl/point_types.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <vector>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/io/point_time.hpp"

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
  if (data == "ascii") {
    long long values_per_point = 0;
    for (std::size_t i = 0; i < n_fields; ++i) values_per_point += keys.count("COUNT") ? std::stoll(keys["COUNT"][i]) : 1;
    for (std::string row; std::getline(in, row);) {
      ++line_no;
      std::istringstream s(row);
      long long k = 0;
      for (std::string tok; s >> tok; ++k) {
        char* end = nullptr;
        std::strtod(tok.c_str(), &end);
        if (end == tok.c_str() || *end != '\0') throw input_error(path, line_no, "not a number: '" + tok + "'");
      }
      if (k != 0 && k != values_per_point) {
        throw input_error(path, line_no, "expected " + std::to_string(values_per_point) + " values");
      }
    }
  }
  if (data == "binary") {
    const std::streamoff body = static_cast<std::streamoff>(in.tellg());
    const auto total = static_cast<long long>(std::filesystem::file_size(path));
    if (body < 0 || total - body < points * point_bytes) {
      throw input_error(path, 0, "PCD body is shorter than POINTS * point size (truncated file?)");
    }
  }
}

// Value of field `f` of point `i` as a double, whatever the field's numeric type.
double field_value(const pcl::PCLPointCloud2& blob, const pcl::PCLPointField& f, std::size_t i) {
  const std::uint8_t* p = blob.data.data() + i * blob.point_step + f.offset;
  auto get = [p](auto v) {
    std::memcpy(&v, p, sizeof v);
    return static_cast<double>(v);
  };
  switch (f.datatype) {
    case pcl::PCLPointField::INT8: return get(std::int8_t{});
    case pcl::PCLPointField::UINT8: return get(std::uint8_t{});
    case pcl::PCLPointField::INT16: return get(std::int16_t{});
    case pcl::PCLPointField::UINT16: return get(std::uint16_t{});
    case pcl::PCLPointField::INT32: return get(std::int32_t{});
    case pcl::PCLPointField::UINT32: return get(std::uint32_t{});
    case pcl::PCLPointField::FLOAT64: return get(double{});
    default: return get(float{});
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
  const pcl::PCLPointField* fx = nullptr;
  const pcl::PCLPointField* fy = nullptr;
  const pcl::PCLPointField* fz = nullptr;
  const pcl::PCLPointField* fi = nullptr;
  const pcl::PCLPointField* ft = nullptr;
  double time_scale = 0.0;
  std::size_t time_rank = time_field_names().size();
  for (const auto& f : blob.fields) {
    if (f.name == "x") fx = &f;
    if (f.name == "y") fy = &f;
    if (f.name == "z") fz = &f;
    if (f.name == "intensity") fi = &f;
    const auto scale = time_field_scale(f.name, f.datatype != pcl::PCLPointField::FLOAT32 &&
                                                    f.datatype != pcl::PCLPointField::FLOAT64);
    const auto rank = static_cast<std::size_t>(
        std::find(time_field_names().begin(), time_field_names().end(), f.name) - time_field_names().begin());
    if (scale && rank < time_rank) {
      ft = &f;
      time_scale = *scale;
      time_rank = rank;
    }
  }
  if (!fx || !fy || !fz) throw input_error(path, 0, "PCD has no x y z fields");
  const std::size_t n = static_cast<std::size_t>(blob.width) * blob.height;
  if (blob.data.size() < n * blob.point_step) throw input_error(path, 0, "PCD body is shorter than its header says");
  PointCloud cloud;
  cloud.reserve(n, fi != nullptr, false);
  std::vector<double> seconds;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d p(field_value(blob, *fx, i), field_value(blob, *fy, i), field_value(blob, *fz, i));
    const Eigen::Vector3f pf = p.cast<float>();
    if (!pf.allFinite()) continue;
    cloud.points.push_back(pf);
    if (fi) {
      const auto v = static_cast<float>(field_value(blob, *fi, i));
      cloud.intensity.push_back(std::isfinite(v) ? v : 0.0f);
    }
    if (ft) {
      const double t = field_value(blob, *ft, i) * time_scale;
      if (!std::isfinite(t))
        throw input_error(path, 0, "point " + std::to_string(i) + ": field '" + ft->name + "' is not a finite number");
      seconds.push_back(t);
    }
  }
  if (ft) cloud.times = relative_times(seconds);
  return cloud;
}

std::string encode_pcd(const PointCloud& cloud) {
  const bool with_i = cloud.has_intensity();
  if (with_i && cloud.intensity.size() != cloud.size()) throw std::invalid_argument("encode_pcd: one intensity per point");
  const std::size_t n = cloud.size();
  std::ostringstream h;
  h << "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS x y z" << (with_i ? " intensity" : "")
    << "\nSIZE 4 4 4" << (with_i ? " 4" : "") << "\nTYPE F F F" << (with_i ? " F" : "") << "\nCOUNT 1 1 1"
    << (with_i ? " 1" : "") << "\nWIDTH " << n << "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " << n
    << "\nDATA binary\n";
  std::string out = h.str();
  const std::size_t stride = with_i ? 4 : 3;
  const std::size_t header = out.size();
  out.resize(header + n * stride * sizeof(float));
  char* p = out.data() + header;
  for (std::size_t i = 0; i < n; ++i) {
    float v[4] = {cloud.points[i].x(), cloud.points[i].y(), cloud.points[i].z(), with_i ? cloud.intensity[i] : 0.0f};
    std::memcpy(p, v, stride * sizeof(float));
    p += stride * sizeof(float);
  }
  return out;
}

}  // namespace tsgraphs::io
