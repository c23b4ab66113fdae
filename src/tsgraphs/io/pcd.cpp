#include "tsgraphs/io/pcd.hpp"

#include <pcl/PCLPointCloud2.h>
#include <pcl/console/print.h>
#include <pcl/conversions.h>
#include <pcl/io/pcd_io.h>
#include <pcl/point_types.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <system_error>
#include <vector>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/io/point_time.hpp"

namespace tsgraphs::io {
namespace {

// PCD's width, height and uncompressed block size are 32-bit words in PCL; a larger header
// value cannot be a real cloud, and bounding it keeps the size arithmetic below from overflowing.
constexpr unsigned long long kMaxPcdDimension = std::numeric_limits<std::uint32_t>::max();
// A field's COUNT beyond this is no real point layout (PCL's largest, a 308-bin histogram).
constexpr unsigned long long kMaxPcdFieldCount = 1u << 16;
// DATA binary_compressed starts with two little-endian words: compressed and uncompressed size.
constexpr std::size_t kCompressedSizeWords = 8;

// A whole-token, non-negative decimal of a header key; anything else (a word, a sign, a
// fraction, an overflow) is an InputError naming the file, the header line and the field.
unsigned long long header_count(const std::string& path, int line_no, const std::string& key,
                                const std::string& value, const std::string& field) {
  unsigned long long v = 0;
  const char* end = value.data() + value.size();
  const auto [ptr, ec] = std::from_chars(value.data(), end, v);
  if (value.empty() || ec != std::errc() || ptr != end) {
    throw input_error(path, line_no,
                      "PCD header: " + key + " '" + value + "' is not a whole number" +
                          (field.empty() ? "" : " (field " + field + ")"));
  }
  return v;
}

// Bytes from `body` to the end of the file, or an InputError naming it.
unsigned long long bytes_after(const std::string& path, std::streamoff body) {
  std::error_code ec;
  const auto total = std::filesystem::file_size(path, ec);
  if (ec) throw input_error(path, 0, "cannot read the file: " + ec.message());
  if (body < 0 || static_cast<unsigned long long>(body) > total) throw input_error(path, 0, "PCD header runs to the end of the file");
  return total - static_cast<unsigned long long>(body);
}

// PCL's reader can crash on a file that is not a PCD (PCL 1.13), so the header is checked
// here first: every key known, FIELDS / SIZE / TYPE / COUNT consistent, POINTS = WIDTH *
// HEIGHT, a binary body long enough for POINTS points, and a binary_compressed block whose
// size words agree with the header and the file (PCL writes through a 0 uncompressed size).
void check_pcd_header(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw input_error(path, 0, "cannot open file");
  std::map<std::string, std::vector<std::string>> keys;
  std::map<std::string, int> key_line;  // where each key was, for messages
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
    // A key given twice is ambiguous: PCL and this check could read different headers (found
    // by fuzzing: a second POINTS line, and PCL sized the cloud by the other one).
    if (keys.count(key)) {
      throw input_error(path, line_no, "PCD header: " + key + " given twice (first on line " + std::to_string(key_line[key]) + ")");
    }
    keys[key] = values;
    key_line[key] = line_no;
    if (key == "DATA") break;
  }
  for (const char* required : {"FIELDS", "SIZE", "TYPE", "WIDTH", "POINTS", "DATA"}) {
    if (!keys.count(required)) throw input_error(path, line_no, std::string("PCD header has no ") + required);
  }
  // PCL's order: the field list before its sizes and counts, sizes before types.
  const auto before = [&](const char* first, const char* then) {
    if (keys.count(then) && key_line[then] < key_line[first]) {
      throw input_error(path, key_line[then], std::string("PCD header: ") + then + " comes before " + first);
    }
  };
  before("FIELDS", "SIZE");
  before("FIELDS", "COUNT");
  before("SIZE", "TYPE");
  if (keys.count("VIEWPOINT") && keys["VIEWPOINT"].size() != 7) {
    throw input_error(path, key_line["VIEWPOINT"], "PCD header: VIEWPOINT needs 7 numbers (tx ty tz qw qx qy qz)");
  }
  const std::size_t n_fields = keys["FIELDS"].size();
  if (n_fields == 0 || keys["SIZE"].size() != n_fields || keys["TYPE"].size() != n_fields ||
      (keys.count("COUNT") && keys["COUNT"].size() != n_fields)) {
    throw input_error(path, 0, "PCD header: FIELDS, SIZE, TYPE and COUNT disagree in length");
  }
  auto number = [&](const std::string& key) -> unsigned long long {
    if (keys[key].size() != 1) throw input_error(path, key_line[key], "PCD header: " + key + " is not one number");
    const unsigned long long v = header_count(path, key_line[key], key, keys[key][0], "");
    if (v > kMaxPcdDimension) {
      throw input_error(path, key_line[key], "PCD header: " + key + " " + keys[key][0] + " is larger than " +
                                                 std::to_string(kMaxPcdDimension));
    }
    return v;
  };
  const unsigned long long width = number("WIDTH");
  const unsigned long long height = keys.count("HEIGHT") ? number("HEIGHT") : 1;
  const unsigned long long points = number("POINTS");
  if (points != width * height) {  // no overflow: both are at most 2^32 - 1
    throw input_error(path, 0, "PCD header: POINTS is not WIDTH * HEIGHT");
  }
  const std::string data = keys["DATA"].empty() ? "" : keys["DATA"][0];
  if (data != "ascii" && data != "binary" && data != "binary_compressed") {
    throw input_error(path, line_no, "PCD header: unknown DATA '" + data + "'");
  }
  unsigned long long point_bytes = 0;
  unsigned long long values_per_point = 0;
  for (std::size_t i = 0; i < n_fields; ++i) {
    const std::string& field = keys["FIELDS"][i];
    const unsigned long long size = header_count(path, key_line["SIZE"], "SIZE", keys["SIZE"][i], field);
    const unsigned long long count =
        keys.count("COUNT") ? header_count(path, key_line["COUNT"], "COUNT", keys["COUNT"][i], field) : 1;
    const std::string& type = keys["TYPE"][i];
    if ((size != 1 && size != 2 && size != 4 && size != 8) || (type != "F" && type != "I" && type != "U") || count < 1 ||
        count > kMaxPcdFieldCount) {
      throw input_error(path, 0, "PCD header: bad SIZE/TYPE/COUNT for field " + field);
    }
    // The types PCL 1.13 reads: floats of 4 or 8 bytes, integers of 1, 2 or 4 (found by
    // fuzzing: a 2-byte F field was read as 4 bytes, past the end of the last point).
    if ((type == "F" && size != 4 && size != 8) || (type != "F" && size == 8)) {
      throw input_error(path, key_line["SIZE"], "PCD header: field " + field + " of TYPE " + type + " and SIZE " +
                                                    std::to_string(size) + ": not a type PCL reads (F 4 or 8, I and U 1, 2 or 4)");
    }
    point_bytes += size * count;
    values_per_point += count;
  }
  // At most 2^32 points of at most (fields x 8 x 2^16) bytes: the product can still overflow.
  unsigned long long body_bytes = 0;
  if (__builtin_mul_overflow(points, point_bytes, &body_bytes)) {
    throw input_error(path, 0, "PCD header: POINTS x point size overflows");
  }
  if (data == "ascii") {
    unsigned long long rows = 0;
    for (std::string row; std::getline(in, row);) {
      ++line_no;
      std::istringstream s(row);
      unsigned long long k = 0;
      for (std::string tok; s >> tok; ++k) {
        char* end = nullptr;
        std::strtod(tok.c_str(), &end);
        if (end == tok.c_str() || *end != '\0') throw input_error(path, line_no, "not a number: '" + tok + "'");
      }
      if (k != 0 && k != values_per_point) {
        throw input_error(path, line_no, "expected " + std::to_string(values_per_point) + " values");
      }
      if (k != 0) ++rows;
    }
    if (rows < points) {
      throw input_error(path, line_no, "PCD body has " + std::to_string(rows) + " points, POINTS says " + std::to_string(points));
    }
  }
  if (data == "binary" || data == "binary_compressed") {
    // PCL's header parser does not stop at DATA: it reads the body's lines on, and takes any
    // that begins with a header word for header (found by fuzzing: it misreads the body, and
    // with FIELDS, COLUMNS or a second DATA writes or reads out of bounds). A binary body with
    // such a line (its bytes spelling one after a newline by accident) is refused.
    const std::streamoff body = static_cast<std::streamoff>(in.tellg());
    static const char* const kHeaderWords[] = {"VERSION", "FIELDS", "COLUMNS", "SIZE", "TYPE", "COUNT",
                                               "WIDTH",   "HEIGHT", "VIEWPOINT", "POINTS", "DATA"};
    for (std::string row; std::getline(in, row);) {
      std::istringstream words(row);
      std::string word;
      if (!(words >> word) || word[0] == '#') continue;
      for (const char* header_word : kHeaderWords) {
        if (word.rfind(header_word, 0) == 0) {
          throw input_error(path, 0, std::string("the binary body after byte ") + std::to_string(body) + " has a line starting '" +
                                         header_word + "', which PCL's reader takes for a header line: it cannot be read");
        }
      }
    }
    in.clear();
    in.seekg(body);
  }
  if (data == "binary") {
    if (bytes_after(path, static_cast<std::streamoff>(in.tellg())) < body_bytes) {
      throw input_error(path, 0, "PCD body is shorter than POINTS * point size (truncated file?)");
    }
  }
  if (data == "binary_compressed") {
    const std::streamoff body = static_cast<std::streamoff>(in.tellg());
    const unsigned long long available = bytes_after(path, body);
    const std::string what = "binary_compressed block at byte " + std::to_string(body) + ": ";
    std::uint8_t words[kCompressedSizeWords] = {};
    if (available < kCompressedSizeWords || !in.read(reinterpret_cast<char*>(words), kCompressedSizeWords)) {
      throw input_error(path, 0, what + "shorter than its two 4-byte size words");
    }
    const auto word = [&](std::size_t at) {  // little-endian, whatever the host
      return static_cast<unsigned long long>(words[at]) | static_cast<unsigned long long>(words[at + 1]) << 8 |
             static_cast<unsigned long long>(words[at + 2]) << 16 | static_cast<unsigned long long>(words[at + 3]) << 24;
    };
    const unsigned long long compressed = word(0), uncompressed = word(4);
    if (uncompressed != body_bytes) {
      throw input_error(path, 0, what + "uncompressed size " + std::to_string(uncompressed) + ", expected " +
                                     std::to_string(body_bytes) + " bytes for POINTS x SIZE");
    }
    if (compressed > available - kCompressedSizeWords) {
      throw input_error(path, 0, what + "compressed size " + std::to_string(compressed) + " runs past the end of the file (" +
                                     std::to_string(available - kCompressedSizeWords) + " bytes follow)");
    }
    if (compressed == 0 && uncompressed > 0) throw input_error(path, 0, what + "compressed size 0 for a non-empty cloud");
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
  // The error_code form: a symlink loop or an unreadable folder is the file's error, not ours.
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec && status.type() != std::filesystem::file_type::not_found) throw input_error(path, 0, "cannot open file: " + ec.message());
  if (!std::filesystem::is_regular_file(status)) throw input_error(path, 0, "no such file");
  check_pcd_header(path);
  // PCL's own lines would come before ours on stderr (its 1.13 has no hook to take them): it
  // is silenced, check_pcd_header has found what it would say, and what is left is named here.
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  pcl::PCLPointCloud2 blob;
  pcl::PCDReader reader;
  int read_status = 0;
  try {
    read_status = reader.read(path, blob);
  } catch (const std::exception& e) {
    // PCL's header parser indexes past a line's words in some files our check accepts (a
    // binary body that starts with the bytes "DATA", found by fuzzing): its error, our line.
    throw input_error(path, 0, std::string("PCL's reader failed on this file (") + e.what() + ")");
  }
  if (read_status < 0) {
    throw input_error(path, 0, "PCD body does not match its header (for binary_compressed: the block does not "
                               "decompress to the size its header gives)");
  }
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
