#include "tsgraphs/io/sequence_folder.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/core/text_file.hpp"
#include "tsgraphs/io/atomic_write.hpp"
#include "tsgraphs/io/coordinate_limit.hpp"
#include "tsgraphs/io/kitti.hpp"

namespace fs = std::filesystem;

namespace tsgraphs::io {
namespace {

void write_binary(const fs::path& path, const void* data, std::size_t bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(static_cast<const char*>(data), static_cast<std::streamsize>(bytes));
  if (!out) throw std::runtime_error(path.string() + ": write failed");
}

void write_text(const fs::path& path, const std::string& text) {
  write_binary(path, text.data(), text.size());
}

std::string read_all(const fs::path& path) { return read_text_file(path.string()); }

std::string format_times(const std::vector<double>& times) {
  std::string out;
  char buf[64];
  for (double t : times) {
    std::snprintf(buf, sizeof(buf), "%.9f\n", t);
    out += buf;
  }
  return out;
}

std::vector<StampedPose> stamp(const std::vector<double>& times, const std::vector<Pose3>& poses) {
  std::vector<StampedPose> out(poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) out[i] = {times[i], poses[i]};
  return out;
}

}  // namespace

std::string scan_stem(std::size_t index) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%06zu", index);
  return buf;
}

namespace {

constexpr const char* kScanExtension = ".bin";

/// Whether `file` is the name of one of the `n` scans times.txt lists (scan_stem(i).bin, i < n).
bool is_listed_scan(const fs::path& file, std::size_t n) {
  const std::string stem = file.stem().string();
  std::size_t index = 0;
  const auto [end, ec] = std::from_chars(stem.data(), stem.data() + stem.size(), index);
  return ec == std::errc() && end == stem.data() + stem.size() && index < n && scan_stem(index) == stem;
}

/// A sequence folder's files agree in number: a scan file beyond the `n` of times.txt and the
/// poses would be left out of the run without a word. The first such file in name order is named.
void check_no_scan_beyond(const fs::path& scans, std::size_t n) {
  std::error_code ec;
  fs::directory_iterator it(scans, ec);
  if (ec) throw input_error(scans.string(), 0, "cannot list the folder: " + ec.message());
  std::string first;
  for (; it != fs::directory_iterator(); it.increment(ec)) {
    const fs::path& p = it->path();
    if (p.extension() == kScanExtension && !is_listed_scan(p.filename(), n) &&
        (first.empty() || p.string() < first))
      first = p.string();
  }
  if (ec) throw input_error(scans.string(), 0, "cannot list the folder: " + ec.message());
  if (!first.empty()) {
    throw input_error(first, 0,
                      "a scan beyond the " + std::to_string(n) +
                          " of times.txt and odom.txt: a sequence folder's files agree in number");
  }
}

}  // namespace

struct SequenceWriter::Impl {
  explicit Impl(const std::string& dir) : folder(dir, "times.txt") {
    fs::create_directories(fs::path(folder.path()) / "scans");
  }
  AtomicDirectory folder;
  std::size_t scans_written = 0;
};

SequenceWriter::SequenceWriter(const std::string& dir) : impl_(std::make_unique<Impl>(dir)) {}
SequenceWriter::~SequenceWriter() = default;

void SequenceWriter::write_scan(std::size_t index, const PointCloud& cloud) {
  const fs::path stem = fs::path(impl_->folder.path()) / "scans" / scan_stem(index);
  std::vector<float> data(cloud.size() * 4);
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    data[4 * i + 0] = cloud.points[i].x();
    data[4 * i + 1] = cloud.points[i].y();
    data[4 * i + 2] = cloud.points[i].z();
    data[4 * i + 3] = cloud.has_intensity() ? cloud.intensity[i] : 0.0f;
  }
  write_binary(stem.string() + kScanExtension, data.data(), data.size() * sizeof(float));
  if (cloud.has_labels()) {
    write_binary(stem.string() + ".label", cloud.labels.data(), cloud.labels.size() * sizeof(std::uint32_t));
  }
  if (cloud.has_times())
    write_binary(stem.string() + ".time", cloud.times.data(), cloud.times.size() * sizeof(float));
  ++impl_->scans_written;
}

void SequenceWriter::commit(const SequenceInfo& info) {
  const fs::path dir = impl_->folder.path();
  if (info.times.size() != impl_->scans_written || info.odometry.size() != info.times.size() ||
      (!info.groundtruth.empty() && info.groundtruth.size() != info.times.size())) {
    throw std::logic_error("SequenceWriter::commit: scans, times and poses disagree in number");
  }
  write_text(dir / "odom.txt", format_tum(stamp(info.times, info.odometry)));
  if (!info.groundtruth.empty())
    write_text(dir / "groundtruth.txt", format_tum(stamp(info.times, info.groundtruth)));
  if (!info.lap_starts.empty()) write_text(dir / "laps.txt", format_times(info.lap_starts));
  if (info.has_rooms) {
    nlohmann::json rooms = nlohmann::json::array();
    for (const RoomTruth& r : info.rooms) {
      nlohmann::json poly = nlohmann::json::array();
      for (const Vec2& p : r.polygon) poly.push_back({p.x(), p.y()});
      rooms.push_back({{"name", r.name}, {"level", r.level}, {"polygon", poly}, {"elevation", r.elevation}});
    }
    write_text(dir / "rooms_gt.json", rooms.dump(2) + "\n");
  }
  for (const auto& [source, inside] : info.attached_files) {
    const fs::path to = dir / inside;
    std::error_code ec;
    fs::create_directories(to.parent_path(), ec);
    if (ec || !fs::copy_file(source, to, fs::copy_options::overwrite_existing, ec) || ec)
      throw input_error(source, 0,
                        "cannot copy into the sequence as " + inside + (ec ? ": " + ec.message() : ""));
  }
  if (!info.scene_yaml.empty()) write_text(dir / "scene.yaml", info.scene_yaml);
  // times.txt last: it marks a folder as a sequence.
  write_text(dir / "times.txt", format_times(info.times));
  impl_->folder.commit();
}

SequenceReader::SequenceReader(const std::string& dir) : dir_(dir) {
  const fs::path d(dir);
  if (!fs::is_directory(d)) throw input_error(dir, 0, "not a folder");
  if (!fs::exists(d / "times.txt"))
    throw input_error((d / "times.txt").string(), 0, "missing: not a sequence folder");
  info_.times = read_times((d / "times.txt").string());
  if (info_.times.empty()) throw input_error((d / "times.txt").string(), 0, "no timestamps");
  const std::size_t n = info_.times.size();
  auto poses_of = [&](const fs::path& p) {
    const std::vector<StampedPose> stamped = read_tum(p.string());
    if (stamped.size() != n) {
      throw input_error(p.string(), 0,
                        "has " + std::to_string(stamped.size()) + " poses but times.txt has " +
                            std::to_string(n) + " scans");
    }
    std::vector<Pose3> poses;
    for (std::size_t i = 0; i < n; ++i) {
      if (std::abs(stamped[i].t - info_.times[i]) > 1e-6) {
        throw input_error(p.string(), static_cast<int>(i) + 1, "timestamp does not match times.txt");
      }
      poses.push_back(stamped[i].pose);
    }
    return poses;
  };
  if (!fs::exists(d / "odom.txt")) throw input_error((d / "odom.txt").string(), 0, "missing");
  info_.odometry = poses_of(d / "odom.txt");
  if (fs::exists(d / "groundtruth.txt")) info_.groundtruth = poses_of(d / "groundtruth.txt");
  if (fs::exists(d / "laps.txt")) info_.lap_starts = read_times((d / "laps.txt").string());
  for (std::size_t i = 0; i < n; ++i) {
    const fs::path bin = d / "scans" / (scan_stem(i) + kScanExtension);
    if (!fs::exists(bin))
      throw input_error(bin.string(), 0, "missing scan (times.txt lists " + std::to_string(n) + ")");
  }
  check_no_scan_beyond(d / "scans", n);
  if (fs::exists(d / "rooms_gt.json")) {
    const std::string path = (d / "rooms_gt.json").string();
    if (fs::is_directory(path)) throw input_error(path, 0, "is a folder, not a file");
    info_.has_rooms = true;
    try {
      const nlohmann::json rooms = nlohmann::json::parse(read_all(path));
      if (!rooms.is_array()) throw input_error(path, 0, "expected a list of rooms");
      for (std::size_t i = 0; i < rooms.size(); ++i) {
        const auto& r = rooms[i];
        RoomTruth room;
        room.name = r.at("name").get<std::string>();
        room.level = r.at("level").get<std::string>();
        room.elevation = r.value("elevation", 0.0);
        for (const auto& p : r.at("polygon")) {
          const Vec2 v(p.at(0).get<double>(), p.at(1).get<double>());
          if (!v.allFinite() || v.cwiseAbs().maxCoeff() > kMaxCoordinate)
            throw input_error(path, 0,
                              "room " + std::to_string(i) + " (" + room.name + "): polygon vertex " +
                                  std::to_string(room.polygon.size()) + " is not a coordinate within 1e8 m");
          room.polygon.push_back(v);
        }
        if (room.polygon.size() < 3)
          throw input_error(path, 0, "room " + std::to_string(i) + ": polygon needs 3 points");
        info_.rooms.push_back(std::move(room));
      }
    } catch (const nlohmann::json::exception& e) {
      throw input_error(path, 0, std::string("malformed: ") + e.what());
    }
  }
}

std::string SequenceReader::scene_path() const {
  const fs::path p = fs::path(dir_) / "scene.yaml";
  return fs::exists(p) ? p.string() : "";
}

namespace {

/// A scan's .label file holding `bytes` for `n` points: an InputError unless one label a point.
void check_label_count(const std::string& path, std::uintmax_t bytes, std::size_t n) {
  if (bytes != n * sizeof(std::uint32_t))
    throw input_error(path, 0,
                      "has " + std::to_string(bytes / 4) + " labels for " + std::to_string(n) + " points");
}

}  // namespace

ScanPresence SequenceReader::presence(std::size_t index) const {
  const fs::path stem = fs::path(dir_) / "scans" / scan_stem(index);
  const KittiBinPresence bin = probe_kitti_bin(stem.string() + kScanExtension);
  const std::string label_path = stem.string() + ".label";
  if (fs::exists(label_path)) {
    std::error_code error;
    const std::uintmax_t bytes = fs::file_size(label_path, error);
    if (error) throw input_error(label_path, 0, "cannot read (" + error.message() + ")");
    check_label_count(label_path, bytes, bin.points);
  }
  ScanPresence p;
  p.empty = bin.points == 0;
  p.has_finite = bin.has_finite;
  p.has_times = fs::exists(stem.string() + ".time");  // its checks are scan()'s, which reads such a scan
  return p;
}

PointCloud SequenceReader::scan(std::size_t index) const {
  const fs::path stem = fs::path(dir_) / "scans" / scan_stem(index);
  PointCloud cloud = read_kitti_bin(stem.string() + kScanExtension);
  const std::size_t n = cloud.size();
  const std::string label_path = stem.string() + ".label";
  if (fs::exists(label_path)) {
    const std::string raw = read_all(label_path);
    check_label_count(label_path, raw.size(), n);
    cloud.labels.resize(n);
    std::memcpy(cloud.labels.data(), raw.data(), raw.size());
    for (std::uint32_t& l : cloud.labels) l &= 0xFFFFu;  // SemanticKITTI: class in the low 16 bits
  }
  const std::string time_path = stem.string() + ".time";
  if (fs::exists(time_path)) {
    const std::string raw = read_all(time_path);
    if (raw.size() != n * sizeof(float))
      throw input_error(
          time_path, 0,
          "has " + std::to_string(raw.size() / 4) + " times for " + std::to_string(n) + " points");
    cloud.times.resize(n);
    std::memcpy(cloud.times.data(), raw.data(), raw.size());
    for (std::size_t i = 0; i < n; ++i)
      if (!std::isfinite(cloud.times[i]))
        throw input_error(time_path, 0, "point " + std::to_string(i) + "'s time is not a finite number");
  }
  return cloud;
}

}  // namespace tsgraphs::io
