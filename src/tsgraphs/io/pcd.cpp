#include "tsgraphs/io/pcd.hpp"

#include <lzf.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <sstream>
#include <string_view>
#include <system_error>
#include <vector>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/core/printable.hpp"
#include "tsgraphs/core/text_file.hpp"
#include "tsgraphs/io/point_time.hpp"

namespace tsgraphs::io {
namespace {

// Width, height and a block's uncompressed size are 32-bit words in PCD as PCL writes it; a
// larger header value cannot be a real cloud, and bounding it keeps the size arithmetic exact.
constexpr unsigned long long kMaxPcdDimension = std::numeric_limits<std::uint32_t>::max();
// A field's COUNT beyond this is no real point layout (PCL's largest, a 308-bin histogram).
constexpr unsigned long long kMaxPcdFieldCount = 1u << 16;
// DATA binary_compressed starts with two little-endian words: compressed and uncompressed size.
constexpr std::size_t kCompressedSizeWords = 8;
// LZF's longest back-reference, 264 bytes, takes 3 bytes: no block expands more than this, so a
// larger uncompressed size word is refused before its buffer is allocated.
constexpr unsigned long long kLzfMaxExpansion = 88;

/// One field of the header, and where its first value is in a point (binary) or a block
/// (binary_compressed stores field after field, each for all points).
struct PcdField {
  std::string name;
  char type = 'F';    // F, I or U
  unsigned size = 4;  // bytes of one value
  unsigned long long count = 1;
  std::size_t offset = 0;  // bytes from the start of a point (binary)
  std::size_t value = 0;   // values from the start of a row (ascii)
};

struct PcdHeader {
  std::vector<PcdField> fields;
  unsigned long long points = 0;
  std::string data;             // ascii, binary or binary_compressed
  std::size_t point_bytes = 0;  // bytes of one point
  std::size_t row_values = 0;   // numbers on one ascii row
  std::size_t body = 0;         // byte where the body starts
  int lines = 0;                // lines up to and including DATA
};

// A whole-token, non-negative decimal of a header key; anything else (a word, a sign, a
// fraction, an overflow) is an InputError naming the file, the header line and the field.
unsigned long long header_count(const std::string& path, int line_no, const std::string& key,
                                const std::string& value, const std::string& field) {
  unsigned long long v = 0;
  const char* end = value.data() + value.size();
  const auto [ptr, ec] = std::from_chars(value.data(), end, v);
  if (value.empty() || ec != std::errc() || ptr != end) {
    throw input_error(path, line_no,
                      "PCD header: " + key + " '" + printable(value) + "' is not a whole number" +
                          (field.empty() ? "" : " (field " + printable(field) + ")"));
  }
  return v;
}

// The header's keys as given: each one's values and its line.
struct PcdKeys {
  std::map<std::string, std::vector<std::string>> values;
  std::map<std::string, int> line;  // where each key was, for messages
};

// The header's lines up to DATA (each key known and given once); sets where the body starts.
PcdKeys read_header_keys(const std::string& path, const std::string& bytes, PcdHeader& h) {
  PcdKeys k;
  auto& keys = k.values;
  auto& key_line = k.line;
  std::size_t at = 0;
  int line_no = 0;
  while (!keys.count("DATA")) {
    if (at >= bytes.size()) {
      throw input_error(path, line_no,
                        bytes.empty() ? "empty file, not a PCD" : "PCD header has no DATA line");
    }
    const std::size_t eol = std::min(bytes.find('\n', at), bytes.size());
    std::string line = bytes.substr(at, eol - at);
    at = eol + 1;
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#') continue;
    std::istringstream s(line);
    std::string key;
    s >> key;
    static const char* const kKnown[] = {"VERSION", "FIELDS", "SIZE",      "TYPE",   "COUNT",
                                         "WIDTH",   "HEIGHT", "VIEWPOINT", "POINTS", "DATA"};
    if (std::find(std::begin(kKnown), std::end(kKnown), key) == std::end(kKnown)) {
      throw input_error(path, line_no, "not a PCD header line: '" + printable(line) + "'");
    }
    std::vector<std::string> values;
    for (std::string v; s >> v;) values.push_back(v);
    if (keys.count(key)) {  // ambiguous: which one holds?
      throw input_error(
          path, line_no,
          "PCD header: " + key + " given twice (first on line " + std::to_string(key_line[key]) + ")");
    }
    keys[key] = values;
    key_line[key] = line_no;
  }
  h.body = std::min(at, bytes.size());
  h.lines = line_no;
  return k;
}

// The required keys there, in the specification's order, VIEWPOINT of 7 numbers and FIELDS /
// SIZE / TYPE / COUNT of one length; `line_no` is the DATA line.
void check_header_keys(const std::string& path, PcdKeys& k, int line_no) {
  auto& keys = k.values;
  auto& key_line = k.line;
  for (const char* required : {"FIELDS", "SIZE", "TYPE", "WIDTH", "POINTS"}) {
    if (!keys.count(required)) throw input_error(path, line_no, std::string("PCD header has no ") + required);
  }
  // The specification's order: the field list before its sizes and counts, sizes before types.
  const auto before = [&](const char* first, const char* then) {
    if (keys.count(then) && key_line[then] < key_line[first]) {
      throw input_error(path, key_line[then], std::string("PCD header: ") + then + " comes before " + first);
    }
  };
  before("FIELDS", "SIZE");
  before("FIELDS", "COUNT");
  before("SIZE", "TYPE");
  if (keys.count("VIEWPOINT") && keys["VIEWPOINT"].size() != 7) {
    throw input_error(path, key_line["VIEWPOINT"],
                      "PCD header: VIEWPOINT needs 7 numbers (tx ty tz qw qx qy qz)");
  }
  const std::size_t n_fields = keys["FIELDS"].size();
  if (n_fields == 0 || keys["SIZE"].size() != n_fields || keys["TYPE"].size() != n_fields ||
      (keys.count("COUNT") && keys["COUNT"].size() != n_fields)) {
    throw input_error(path, key_line["FIELDS"],
                      "PCD header: FIELDS, SIZE, TYPE and COUNT disagree in length");
  }
}

// WIDTH, HEIGHT or POINTS: one whole number of at most 32 bits.
unsigned long long header_dimension(const std::string& path, PcdKeys& k, const std::string& key) {
  auto& keys = k.values;
  auto& key_line = k.line;
  if (keys[key].size() != 1)
    throw input_error(path, key_line[key], "PCD header: " + key + " is not one number");
  const unsigned long long v = header_count(path, key_line[key], key, keys[key][0], "");
  if (v > kMaxPcdDimension) {
    throw input_error(
        path, key_line[key],
        "PCD header: " + key + " " + keys[key][0] + " is larger than " + std::to_string(kMaxPcdDimension));
  }
  return v;
}

// Field `i`'s name, type, size and count (a PCD type, a count of 1 to 2^16); no offsets yet.
PcdField header_field(const std::string& path, PcdKeys& k, std::size_t i) {
  auto& keys = k.values;
  auto& key_line = k.line;
  PcdField f;
  f.name = keys["FIELDS"][i];
  const unsigned long long size = header_count(path, key_line["SIZE"], "SIZE", keys["SIZE"][i], f.name);
  f.count =
      keys.count("COUNT") ? header_count(path, key_line["COUNT"], "COUNT", keys["COUNT"][i], f.name) : 1;
  const std::string& type = keys["TYPE"][i];
  if (type != "F" && type != "I" && type != "U") {
    throw input_error(
        path, key_line["TYPE"],
        "PCD header: TYPE '" + printable(type) + "' of field " + printable(f.name) + " is not F, I or U");
  }
  // The specification's types: floats of 4 or 8 bytes, integers of 1, 2, 4 or 8 (a 2-byte
  // float has no C type; one was read as 4 bytes, past the last point: found by fuzzing).
  const bool known =
      type == "F" ? (size == 4 || size == 8) : (size == 1 || size == 2 || size == 4 || size == 8);
  if (!known) {
    throw input_error(path, key_line["SIZE"],
                      "PCD header: field " + printable(f.name) + " of TYPE " + type + " and SIZE " +
                          std::to_string(size) + ": not a PCD type (F 4 or 8, I and U 1, 2, 4 or 8)");
  }
  if (f.count < 1 || f.count > kMaxPcdFieldCount) {
    throw input_error(path, key_line.count("COUNT") ? key_line["COUNT"] : key_line["FIELDS"],
                      "PCD header: COUNT of field " + printable(f.name) + " must be 1 to " +
                          std::to_string(kMaxPcdFieldCount));
  }
  f.type = type[0];
  f.size = static_cast<unsigned>(size);
  return f;
}

// The header (PCD v0.7: every key known and given once, in the specification's order, FIELDS /
// SIZE / TYPE / COUNT of one length, POINTS = WIDTH * HEIGHT), or an InputError at its line.
PcdHeader parse_header(const std::string& path, const std::string& bytes) {
  PcdHeader h;
  PcdKeys k = read_header_keys(path, bytes, h);
  check_header_keys(path, k, h.lines);
  auto& keys = k.values;
  auto& key_line = k.line;
  const unsigned long long width = header_dimension(path, k, "WIDTH");
  const unsigned long long height = keys.count("HEIGHT") ? header_dimension(path, k, "HEIGHT") : 1;
  h.points = header_dimension(path, k, "POINTS");
  if (h.points != width * height) {  // no overflow: both are at most 2^32 - 1
    throw input_error(path, key_line["POINTS"],
                      "PCD header: POINTS " + std::to_string(h.points) + " is not WIDTH * HEIGHT (" +
                          std::to_string(width) + " x " + std::to_string(height) + ")");
  }
  h.data = keys["DATA"].size() == 1 ? keys["DATA"][0] : "";
  if (h.data != "ascii" && h.data != "binary" && h.data != "binary_compressed") {
    throw input_error(path, key_line["DATA"], "PCD header: DATA must be ascii, binary or binary_compressed");
  }
  for (std::size_t i = 0; i < keys["FIELDS"].size(); ++i) {
    PcdField f = header_field(path, k, i);
    f.offset = h.point_bytes;
    f.value = h.row_values;
    h.point_bytes += f.size * f.count;  // fields (< file size) x 8 x 2^16: no overflow
    h.row_values += f.count;
    h.fields.push_back(f);
  }
  // POINTS (< 2^32) times that can overflow: a header this large describes no file.
  unsigned long long body_bytes = 0, body_values = 0;
  if (__builtin_mul_overflow(h.points, h.point_bytes, &body_bytes) ||
      __builtin_mul_overflow(h.points, h.row_values, &body_values)) {
    throw input_error(path, key_line["POINTS"], "PCD header: POINTS x point size overflows");
  }
  return h;
}

// A value of field `f` at `p` as a double, whatever its numeric type.
double decode(const std::uint8_t* p, const PcdField& f) {
  auto get = [p](auto v) {
    std::memcpy(&v, p, sizeof v);
    return static_cast<double>(v);
  };
  switch (f.type) {
    case 'F':
      return f.size == 4 ? get(float{}) : get(double{});
    case 'I':
      switch (f.size) {
        case 1:
          return get(std::int8_t{});
        case 2:
          return get(std::int16_t{});
        case 4:
          return get(std::int32_t{});
        default:
          return get(std::int64_t{});
      }
    default:
      switch (f.size) {
        case 1:
          return get(std::uint8_t{});
        case 2:
          return get(std::uint16_t{});
        case 4:
          return get(std::uint32_t{});
        default:
          return get(std::uint64_t{});
      }
  }
}

/// The body's values: value(f, i) is the first value of field f of point i.
class PcdBody {
 public:
  PcdBody(const std::string& path, const std::string& bytes, const PcdHeader& h)
      : h_(h), ascii_body_(h.data == "ascii") {
    if (ascii_body_) read_ascii(path, bytes);
    if (h.data == "binary") {
      const unsigned long long available = bytes.size() - h.body;
      const unsigned long long needed = h.points * h.point_bytes;  // no overflow (parse_header)
      if (available < needed) {
        throw input_error(path, 0,
                          "PCD body after byte " + std::to_string(h.body) + " has " +
                              std::to_string(available) + " bytes, POINTS x point size is " +
                              std::to_string(needed) + " (truncated file?)");
      }
      if (available > needed) {  // as an ascii body with rows after the last point
        throw input_error(path, 0,
                          "PCD body has more points than POINTS (" + std::to_string(h.points) +
                              "): " + std::to_string(available - needed) +
                              " bytes after the last point, from byte " + std::to_string(h.body + needed));
      }
      binary_ = reinterpret_cast<const std::uint8_t*>(bytes.data()) + h.body;
    }
    if (h.data == "binary_compressed") read_compressed(path, bytes);
  }

  double value(const PcdField& f, std::size_t i) const {
    if (ascii_body_) return ascii_[i * h_.row_values + f.value];
    if (binary_) return decode(binary_ + i * h_.point_bytes + f.offset, f);
    // Field after field: a field's block starts after all points' values of the ones before.
    return decode(block_.data() + f.offset * h_.points + i * f.size * f.count, f);
  }

 private:
  void read_ascii(const std::string& path, const std::string& bytes) {
    ascii_.reserve(std::min<unsigned long long>(h_.points * h_.row_values, bytes.size()));
    unsigned long long rows = 0;
    int line_no = h_.lines;
    std::string token;
    for (std::size_t at = h_.body; at < bytes.size();) {
      const std::size_t eol = std::min(bytes.find('\n', at), bytes.size());
      const std::string_view line(bytes.data() + at, eol - at);
      at = eol + 1;
      ++line_no;
      std::size_t k = 0;
      for (std::size_t t = line.find_first_not_of(" \t\r"); t != std::string_view::npos;
           t = line.find_first_not_of(" \t\r", t)) {
        const std::size_t end = std::min(line.find_first_of(" \t\r", t), line.size());
        token.assign(line.substr(t, end - t));
        t = end;
        char* stop = nullptr;
        const double v = std::strtod(token.c_str(), &stop);  // reads nan and inf, as PCD writers do
        if (stop == token.c_str() || *stop != '\0')
          throw input_error(path, line_no, "not a number: '" + printable(token) + "'");
        if (rows >= h_.points)
          throw input_error(path, line_no,
                            "PCD body has more points than POINTS (" + std::to_string(h_.points) + ")");
        ascii_.push_back(v);
        ++k;
      }
      if (k != 0 && k != h_.row_values) {
        throw input_error(
            path, line_no,
            "expected " + std::to_string(h_.row_values) + " values, found " + std::to_string(k));
      }
      if (k != 0) ++rows;
    }
    if (rows < h_.points) {
      throw input_error(
          path, line_no,
          "PCD body has " + std::to_string(rows) + " points, POINTS says " + std::to_string(h_.points));
    }
  }

  void read_compressed(const std::string& path, const std::string& bytes) {
    const unsigned long long available = bytes.size() - h_.body;
    const std::string what = "binary_compressed block at byte " + std::to_string(h_.body) + ": ";
    if (available < kCompressedSizeWords)
      throw input_error(path, 0, what + "shorter than its two 4-byte size words");
    const auto* words = reinterpret_cast<const std::uint8_t*>(bytes.data()) + h_.body;
    const auto word = [&](std::size_t at) {  // little-endian, whatever the host
      return static_cast<unsigned long long>(words[at]) |
             static_cast<unsigned long long>(words[at + 1]) << 8 |
             static_cast<unsigned long long>(words[at + 2]) << 16 |
             static_cast<unsigned long long>(words[at + 3]) << 24;
    };
    const unsigned long long compressed = word(0), uncompressed = word(4);
    const unsigned long long expected = h_.points * h_.point_bytes;  // no overflow (parse_header)
    if (uncompressed != expected) {
      throw input_error(path, 0,
                        what + "uncompressed size " + std::to_string(uncompressed) + ", expected " +
                            std::to_string(expected) + " bytes for POINTS x SIZE");
    }
    if (compressed > available - kCompressedSizeWords) {
      throw input_error(path, 0,
                        what + "compressed size " + std::to_string(compressed) +
                            " runs past the end of the file (" +
                            std::to_string(available - kCompressedSizeWords) + " bytes follow)");
    }
    // As a binary body longer than POINTS: bytes past the block are no part of the cloud.
    if (compressed < available - kCompressedSizeWords) {
      const unsigned long long end = h_.body + kCompressedSizeWords + compressed;
      throw input_error(path, 0,
                        what + std::to_string(bytes.size() - end) +
                            " bytes after the compressed block, from byte " + std::to_string(end));
    }
    if (expected == 0) return;
    if (compressed == 0) throw input_error(path, 0, what + "compressed size 0 for a non-empty cloud");
    if (uncompressed > compressed * kLzfMaxExpansion) {
      throw input_error(path, 0,
                        what + std::to_string(compressed) + " compressed bytes cannot hold " +
                            std::to_string(uncompressed) + " (LZF expands at most " +
                            std::to_string(kLzfMaxExpansion) + " times)");
    }
    block_.resize(uncompressed);
    // liblzf checks every back-reference and length against both buffers (CHECK_INPUT).
    const unsigned int got =
        lzf_decompress(words + kCompressedSizeWords, static_cast<unsigned int>(compressed), block_.data(),
                       static_cast<unsigned int>(uncompressed));
    if (got != uncompressed) {
      throw input_error(path, 0,
                        what + "corrupt LZF data: it decompresses to " + std::to_string(got) + " of " +
                            std::to_string(uncompressed) + " bytes");
    }
  }

  const PcdHeader& h_;
  const bool ascii_body_;
  std::vector<double> ascii_;             // ascii: row after row
  const std::uint8_t* binary_ = nullptr;  // binary: the file's bytes, point after point
  std::vector<std::uint8_t> block_;       // binary_compressed: decompressed, field after field
};

}  // namespace

PointCloud read_pcd(const std::string& path) {
  // The error_code form: a symlink loop or an unreadable folder is the file's error, not ours.
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec && status.type() != std::filesystem::file_type::not_found)
    throw input_error(path, 0, "cannot open file: " + ec.message());
  if (!std::filesystem::is_regular_file(status)) throw input_error(path, 0, "no such file");
  const std::string bytes = read_text_file(path);
  const PcdHeader h = parse_header(path, bytes);
  const PcdField* fx = nullptr;
  const PcdField* fy = nullptr;
  const PcdField* fz = nullptr;
  const PcdField* fi = nullptr;
  const PcdField* ft = nullptr;
  double time_scale = 0.0;
  std::size_t time_rank = time_field_names().size();
  for (const auto& f : h.fields) {
    if (f.name == "x") fx = &f;
    if (f.name == "y") fy = &f;
    if (f.name == "z") fz = &f;
    if (f.name == "intensity") fi = &f;
    const auto scale = time_field_scale(f.name, f.type != 'F');
    const auto rank = static_cast<std::size_t>(
        std::find(time_field_names().begin(), time_field_names().end(), f.name) - time_field_names().begin());
    if (scale && rank < time_rank) {
      ft = &f;
      time_scale = *scale;
      time_rank = rank;
    }
  }
  if (!fx || !fy || !fz) throw input_error(path, 0, "PCD has no x y z fields");
  const PcdBody body(path, bytes, h);
  const auto n = static_cast<std::size_t>(h.points);
  PointCloud cloud;
  cloud.reserve(n, fi != nullptr, false);
  std::vector<double> seconds;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d p(body.value(*fx, i), body.value(*fy, i), body.value(*fz, i));
    const Eigen::Vector3f pf = p.cast<float>();
    if (!pf.allFinite()) continue;  // organised clouds carry NaNs for missing returns
    cloud.points.push_back(pf);
    if (fi) {
      const auto v = static_cast<float>(body.value(*fi, i));
      cloud.intensity.push_back(std::isfinite(v) ? v : 0.0f);
    }
    if (ft) {
      const double t = body.value(*ft, i) * time_scale;
      if (!std::isfinite(t))
        throw input_error(
            path, 0,
            "point " + std::to_string(i) + ": field '" + printable(ft->name) + "' is not a finite number");
      seconds.push_back(t);
    }
  }
  if (ft) cloud.times = relative_times(seconds);
  return cloud;
}

std::string encode_pcd(const PointCloud& cloud) {
  const bool with_i = cloud.has_intensity();
  if (with_i && cloud.intensity.size() != cloud.size())
    throw std::invalid_argument("encode_pcd: one intensity per point");
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
    float v[4] = {cloud.points[i].x(), cloud.points[i].y(), cloud.points[i].z(),
                  with_i ? cloud.intensity[i] : 0.0f};
    std::memcpy(p, v, stride * sizeof(float));
    p += stride * sizeof(float);
  }
  return out;
}

}  // namespace tsgraphs::io
