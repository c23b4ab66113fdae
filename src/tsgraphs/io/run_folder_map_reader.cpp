// A run folder's map.ply read: binary little-endian vertices, every coordinate checked.
#include "tsgraphs/io/run_folder.hpp"

#include <charconv>
#include <cstdint>
#include <cstring>
#include <sstream>
#include <vector>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/core/printable.hpp"
#include "tsgraphs/core/text_file.hpp"
#include "tsgraphs/io/run_folder_internal.hpp"

namespace tsgraphs::io {

using namespace run_folder_internal;

namespace {

// map.ply's vertex: x y z (double, or float in runs older than the map frame), then the colour.
constexpr std::size_t kPlyAxes = 3;
constexpr std::size_t kPlyColourBytes = 3;  // uchar red, green, blue
const char* const kPlyAxisNames[kPlyAxes] = {"x", "y", "z"};

template <class Scalar>
std::size_t ply_vertex_bytes() {
  return kPlyAxes * sizeof(Scalar) + kPlyColourBytes;
}

// Vertex `i` of the body at `v`: every coordinate finite and within kMaxCoordinate (a header
// saying float over doubles reads as values up to 3e38), or a FieldError naming it.
template <class Scalar>
MapVertex ply_vertex(const char* v, std::size_t i) {
  Scalar xyz[kPlyAxes];
  std::memcpy(xyz, v, sizeof xyz);
  MapVertex out;
  for (std::size_t a = 0; a < kPlyAxes; ++a) {
    out.p[static_cast<Eigen::Index>(a)] =
        bounded_coordinate(static_cast<double>(xyz[a]), item("vertex", i) + "." + kPlyAxisNames[a]);
  }
  const char* colour = v + sizeof xyz;
  out.r = static_cast<std::uint8_t>(colour[0]), out.g = static_cast<std::uint8_t>(colour[1]),
  out.b = static_cast<std::uint8_t>(colour[2]);
  return out;
}

// The `count` vertices of the body at byte `at` of `bytes`, which must end with the last one:
// a body short of the count, or bytes after it (a header saying float over doubles, a file
// appended to), is an InputError naming the file and the byte.
template <class Scalar>
std::vector<MapVertex> ply_vertices(const std::string& path, const std::string& bytes, std::size_t at,
                                    std::size_t count) {
  const std::size_t stride = ply_vertex_bytes<Scalar>(), body = bytes.size() - at;
  if (body / stride < count) {
    throw input_error(path, 0,
                      "holds " + std::to_string(body / stride) + " vertices of " + std::to_string(stride) +
                          " bytes from byte " + std::to_string(at) + ", its header says " +
                          std::to_string(count));
  }
  if (body != count * stride) {  // no overflow: count * stride <= body
    throw input_error(path, 0,
                      std::to_string(body - count * stride) + " bytes after the last of the header's " +
                          std::to_string(count) + " vertices of " + std::to_string(stride) +
                          " bytes, from byte " + std::to_string(at + count * stride) +
                          " (are the properties' types the body's?)");
  }
  std::vector<MapVertex> out(count);
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t offset = at + i * stride;
    try {
      out[i] = ply_vertex<Scalar>(bytes.data() + offset, i);
    } catch (const FieldError& e) {
      throw input_error(path, 0, std::string("byte ") + std::to_string(offset) + ": " + e.what());
    }
  }
  return out;
}

}  // namespace

std::vector<MapVertex> read_map_ply(const std::string& path) {
  const std::string bytes = read_text_file(path);
  const std::string end = "end_header\n";
  const std::size_t body = bytes.find(end);
  if (bytes.rfind("ply\nformat binary_little_endian 1.0\n", 0) != 0 || body == std::string::npos) {
    throw input_error(path, 1, "not a binary little-endian PLY file");
  }
  std::istringstream header(bytes.substr(0, body));
  std::size_t count = 0;
  std::vector<std::string> properties;
  int line_no = 0;
  for (std::string line; std::getline(header, line);) {
    ++line_no;
    std::istringstream words(line);
    std::string key, a, b;
    words >> key >> a >> b;
    if (key == "element" && a == "vertex") {
      unsigned long long n = 0;
      const auto [ptr, ec] = std::from_chars(b.data(), b.data() + b.size(), n);
      if (ec != std::errc() || ptr != b.data() + b.size())
        throw input_error(path, line_no, "vertex count '" + printable(b) + "' is not a whole number");
      count = static_cast<std::size_t>(n);
    }
    if (key == "property") properties.push_back(a + " " + b);
  }
  const bool doubles = properties == std::vector<std::string>{"double x",  "double y",    "double z",
                                                              "uchar red", "uchar green", "uchar blue"};
  const bool floats = properties == std::vector<std::string>{"float x",   "float y",     "float z",
                                                             "uchar red", "uchar green", "uchar blue"};
  if (!doubles && !floats)
    throw input_error(path, 0, "vertices are not x y z (float or double) then red green blue (uchar)");
  const std::size_t at = body + end.size();
  return doubles ? ply_vertices<double>(path, bytes, at, count) : ply_vertices<float>(path, bytes, at, count);
}

}  // namespace tsgraphs::io
