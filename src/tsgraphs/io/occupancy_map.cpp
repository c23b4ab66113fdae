#include "tsgraphs/io/occupancy_map.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/core/printable.hpp"
#include "tsgraphs/core/text_file.hpp"
#include "tsgraphs/core/yaml_map.hpp"

namespace tsgraphs::io {
namespace {

constexpr double kMaxResolution = 10.0;  // m per pixel: beyond this no indoor map makes sense
constexpr int kRawUnknownAbove =
    100;  // raw mode: occupancy is in percent, ROS's -1 (255) and beyond mean unknown

bool parse_negate(const YamlMap& m) {
  if (!m.has("negate")) return false;
  const std::string v = m.require<std::string>("negate");
  // map_server writes 0 / 1; YAML's true / false are read too.
  if (v == "0" || v == "false" || v == "False" || v == "FALSE") return false;
  if (v == "1" || v == "true" || v == "True" || v == "TRUE") return true;
  throw m.error("negate", "expected 0 or 1 (got '" + printable(v) + "')");
}

double threshold(const YamlMap& m, const std::string& key, double fallback) {
  const double v = m.get<double>(key, fallback);
  if (v < 0.0 || v > 1.0) throw m.error(key, "must lie in [0, 1]");
  return v;
}

}  // namespace

MapMetadata parse_map_yaml(const std::string& text, const std::string& file, const std::string& base_dir) {
  const YamlMap m = YamlMap::load_string(text, file);
  m.check_keys({"image", "resolution", "origin", "negate", "occupied_thresh", "free_thresh", "mode"});
  MapMetadata meta;
  meta.yaml_file = file;
  const std::string image = m.require<std::string>("image");
  if (image.empty()) throw m.error("image", "is empty");
  const std::filesystem::path p(image);
  meta.image =
      p.is_absolute() ? p.string() : (std::filesystem::path(base_dir) / p).lexically_normal().string();
  meta.resolution = m.require<double>("resolution");
  if (!(meta.resolution > 0.0) || meta.resolution > kMaxResolution)
    throw m.error("resolution",
                  "must lie in (0, " + std::to_string(static_cast<int>(kMaxResolution)) + "] m per pixel");
  if (!m.has("origin")) throw m.error_here("missing required key 'origin' ([x, y, yaw])");
  const YAML::Node o = m.raw("origin");
  if (!o.IsSequence() || o.size() != 3) throw m.error("origin", "expected [x, y, yaw]");
  meta.origin_x = m.as<double>(o[0], m.key_path("origin"));
  meta.origin_y = m.as<double>(o[1], m.key_path("origin"));
  meta.origin_yaw = m.as<double>(o[2], m.key_path("origin"));
  meta.negate = parse_negate(m);
  meta.occupied_thresh = threshold(m, "occupied_thresh", meta.occupied_thresh);
  meta.free_thresh = threshold(m, "free_thresh", meta.free_thresh);
  if (meta.free_thresh > meta.occupied_thresh)
    throw m.error("free_thresh", "must not exceed occupied_thresh");
  const std::string mode = m.get<std::string>("mode", "trinary");
  if (mode == "trinary")
    meta.mode = MapMode::kTrinary;
  else if (mode == "scale")
    meta.mode = MapMode::kScale;
  else if (mode == "raw")
    meta.mode = MapMode::kRaw;
  else
    throw m.error("mode", "unknown mode '" + printable(mode) + "' (trinary, scale, raw)");
  return meta;
}

MapMetadata read_map_yaml(const std::string& file) {
  const std::string text = read_text_file(file);
  const std::string base = std::filesystem::path(file).parent_path().string();
  return parse_map_yaml(text, file, base.empty() ? "." : base);
}

OccupancyMap classify(const Image& image, const MapMetadata& meta) {
  OccupancyMap map;
  map.meta = meta;
  map.width = image.width;
  map.height = image.height;
  map.cells.resize(static_cast<std::size_t>(image.width) * image.height);
  // map_server averages every channel in trinary mode (alpha too) and the colour channels
  // otherwise. Its reader turns grey + alpha into RGBA, so the grey counts three times.
  const bool alpha_in_mean = meta.mode == MapMode::kTrinary || !image.has_alpha();
  const int n = image.channels;
  for (int j = 0; j < image.height; ++j) {
    for (int i = 0; i < image.width; ++i) {
      const std::uint8_t* p = image.samples.data() + (static_cast<std::size_t>(j) * image.width + i) * n;
      int sum = 0, count = 0;
      if (n <= 2) {
        sum = n == 2 ? 3 * p[0] : p[0];
        count = n == 2 ? 3 : 1;
      } else {
        sum = p[0] + p[1] + p[2];
        count = 3;
      }
      if (image.has_alpha() && alpha_in_mean) {
        sum += p[n - 1];
        ++count;
      }
      double avg = sum / static_cast<double>(count);
      if (meta.negate) avg = 255 - avg;
      CellState state = CellState::kUnknown;
      if (meta.mode == MapMode::kRaw) {
        const int value = static_cast<int>(static_cast<unsigned char>(avg));  // map_server's cast
        const double occ = value / 100.0;
        if (value > kRawUnknownAbove)
          state = CellState::kUnknown;
        else if (occ > meta.occupied_thresh)
          state = CellState::kOccupied;
        else if (occ < meta.free_thresh)
          state = CellState::kFree;
      } else {
        const double occ = (255 - avg) / 255.0;
        if (occ > meta.occupied_thresh)
          state = CellState::kOccupied;
        else if (occ < meta.free_thresh)
          state = CellState::kFree;
      }
      // The image's row 0 is the map's top: cell row height - 1 - j.
      map.cells[static_cast<std::size_t>(image.height - 1 - j) * image.width + i] = state;
    }
  }
  return map;
}

OccupancyMap read_occupancy_map(const std::string& yaml_file) {
  const MapMetadata meta = read_map_yaml(yaml_file);
  std::error_code ec;
  if (!std::filesystem::is_regular_file(meta.image, ec)) {
    // Name the YAML's line too: the image key is what points nowhere.
    const YamlMap m = YamlMap::load_file(yaml_file);
    throw m.error("image", "no such image file: " + printable(meta.image, kMaxQuotedPathBytes));
  }
  return classify(read_image(meta.image), meta);
}

}  // namespace tsgraphs::io
