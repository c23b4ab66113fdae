#include "tsgraphs/io/scan_folder.hpp"

#include <glob.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <system_error>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/io/kitti.hpp"
#include "tsgraphs/io/pcd.hpp"
#include "tsgraphs/io/tum.hpp"

namespace tsgraphs::io {

namespace {

namespace fs = std::filesystem;

constexpr int kTumFields = 8;     // t x y z qx qy qz qw
constexpr int kKittiFields = 12;  // a 3x4 matrix
// Stamps written with microseconds agree to this whatever their precision (s).
constexpr double kStampTolerance = 1e-6;

/// Whether `p` is a regular file. The error_code forms throughout this file: a symlink loop or
/// an unreadable entry is an InputError naming it, not std::filesystem's exception.
bool is_file(const fs::path& p) {
  std::error_code ec;
  const fs::file_status status = fs::status(p, ec);
  if (ec && status.type() != fs::file_type::not_found)
    throw input_error(p.string(), 0, "cannot read: " + ec.message());
  return fs::is_regular_file(status);
}

/// Whether `p` is a folder; false for anything that cannot be looked at.
bool is_folder(const fs::path& p) {
  std::error_code ec;
  return fs::is_directory(p, ec);
}

bool is_scan_name(const fs::path& p) { return p.extension() == ".pcd" || p.extension() == ".bin"; }

/// The .pcd and .bin files directly in `dir`, in name order.
std::vector<std::string> scan_files_in(const fs::path& dir) {
  std::vector<std::string> files;
  if (!is_folder(dir)) return files;
  std::error_code ec;
  fs::directory_iterator it(dir, ec);
  if (ec) throw input_error(dir.string(), 0, "cannot list the folder: " + ec.message());
  std::vector<std::string> names;
  for (; it != fs::directory_iterator(); it.increment(ec)) {
    if (is_scan_name(it->path())) names.push_back(it->path().string());
  }
  if (ec) throw input_error(dir.string(), 0, "cannot list the folder: " + ec.message());
  std::sort(names.begin(), names.end());  // in name order, so that a bad entry is always the same one
  for (const std::string& n : names)
    if (is_file(n)) files.push_back(n);
  return files;
}

std::vector<std::string> glob_files(const std::string& pattern) {
  glob_t g{};
  std::vector<std::string> matches;
  if (::glob(pattern.c_str(), 0, nullptr, &g) == 0) matches.assign(g.gl_pathv, g.gl_pathv + g.gl_pathc);
  ::globfree(&g);  // before is_file, which throws for a symlink loop (LeakSanitizer found the leak)
  std::vector<std::string> files;
  for (const std::string& m : matches)
    if (is_file(m)) files.push_back(m);
  std::sort(files.begin(), files.end());
  return files;
}

/// The first of `names` that exists in one of `dirs`, or "".
std::string find_beside(const std::vector<fs::path>& dirs, const std::vector<std::string>& names) {
  for (const fs::path& d : dirs)
    for (const std::string& n : names)
      if (is_file(d / n)) return (d / n).string();
  return "";
}

}  // namespace

bool is_sequence_folder(const std::string& dir) {
  const fs::path d(dir);
  return is_file(d / "times.txt") && is_file(d / "odom.txt") && is_folder(d / "scans");
}

namespace {

// TUM poses carry their own stamps: each must be its scan's time, up to one offset for all
// (times.txt may count from the start, the poses in Unix time). A pose nearer another scan's
// time than its own (half the gap to a neighbour) belongs to another scan.
void check_stamps_agree(const std::string& poses, const std::vector<double>& pose_stamps,
                        const std::string& times, const std::vector<double>& scan_times) {
  const double offset = pose_stamps.front() - scan_times.front();
  for (std::size_t i = 0; i < scan_times.size(); ++i) {
    double gap = std::numeric_limits<double>::infinity();
    if (i > 0) gap = std::min(gap, scan_times[i] - scan_times[i - 1]);
    if (i + 1 < scan_times.size()) gap = std::min(gap, scan_times[i + 1] - scan_times[i]);
    const double off = std::abs(pose_stamps[i] - offset - scan_times[i]);
    if (off > kStampTolerance && !(off < 0.5 * gap)) {
      char what[200];
      std::snprintf(what, sizeof what,
                    "pose %zu: stamp %.6f is %.6g s from the scan's time in %s (offset %.6f s): "
                    "not this scan's pose",
                    i + 1, pose_stamps[i], off, times.c_str(), offset);
      throw input_error(poses, 0, what);
    }
  }
}

// For a count of poses or times short of the scans: the first scan file left without one, which
// the count would silently drop were it read as far as it goes.
std::string first_beyond(const std::vector<std::string>& files, std::size_t count, const char* what) {
  if (count >= files.size()) return "";
  return std::string(": the first scan without a ") + what + " is " + files[count];
}

// A sequence folder that lost a file: say which, not "no scans"; else say where scans were looked for.
[[noreturn]] void throw_no_scans(const std::string& folder) {
  const fs::path d(folder);
  const std::size_t in_scans = scan_files_in(d / "scans").size();
  if (in_scans > 0) {
    std::string missing;
    for (const char* f : {"times.txt", "odom.txt"})
      if (!is_file(d / f)) missing += std::string(missing.empty() ? "" : " and ") + f;
    throw input_error(folder, 0,
                      "scans/ holds " + std::to_string(in_scans) + " scans but " + missing +
                          (missing.find(" and ") != std::string::npos ? " are" : " is") +
                          " missing: a sequence folder needs times.txt and odom.txt (to run the scans alone, "
                          "--scans '" +
                          (d / "scans").string() + "/*')");
  }
  throw input_error(
      folder, 0,
      "no scans: neither a sequence folder (times.txt, odom.txt, scans/) nor .pcd or .bin files "
      "(in it or in velodyne/)");
}

// The scans of `folder` or, if it has none, of its velodyne/ (KITTI's layout).
std::vector<std::string> scans_in_folder(const std::string& folder) {
  if (!is_folder(folder)) throw input_error(folder, 0, "not a folder");
  std::vector<std::string> files = scan_files_in(folder);
  if (files.empty()) files = scan_files_in(fs::path(folder) / "velodyne");
  if (files.empty()) throw_no_scans(folder);
  return files;
}

// Whether the scans are .pcd (else KITTI .bin); scans of both kinds, or of neither, are an error.
bool scans_are_pcd(const std::vector<std::string>& files) {
  const auto is_pcd = [](const std::string& f) { return fs::path(f).extension() == ".pcd"; };
  const bool pcd = is_pcd(files.front());
  for (const std::string& f : files) {
    if (is_pcd(f) != pcd)
      throw input_error(f, 0,
                        std::string("a ") + (pcd ? ".bin" : ".pcd") + " scan among " +
                            (pcd ? ".pcd" : ".bin") + " scans: pass --scans GLOB");
    if (!is_pcd(f) && fs::path(f).extension() != ".bin")
      throw input_error(f, 0, "not a scan (.pcd or KITTI .bin): narrow --scans");
  }
  return pcd;
}

// The pose file's format: "none" without one, the one asked for, or for auto the one its first
// line's field count tells.
std::string pose_format(const std::string& poses, const std::string& requested) {
  std::string format = poses.empty() ? "none" : requested;
  if (format == "auto") {
    const int fields = fields_on_first_line(poses);
    if (fields == kTumFields)
      format = "tum";
    else if (fields == kKittiFields)
      format = "kitti";
    else
      throw input_error(poses, 0,
                        std::to_string(fields) +
                            " fields on the first line: neither TUM (8) nor KITTI (12); "
                            "set --pose-format");
  }
  return format;
}

// The poses of `poses` into `odometry`; their stamps when they have them (TUM), else none.
std::vector<double> read_poses(const std::string& poses, const std::string& format,
                               std::vector<Pose3>& odometry) {
  std::vector<double> pose_stamps;
  if (format == "tum") {
    for (const StampedPose& p : read_tum(poses)) {
      pose_stamps.push_back(p.t);
      odometry.push_back(p.pose);
    }
  } else if (format == "kitti") {
    odometry = read_kitti_poses(poses);
  } else if (format != "none") {
    throw input_error(poses, 0, "pose format '" + format + "': expected tum, kitti or auto");
  }
  return pose_stamps;
}

// The times of a times file, one per scan, agreeing with the poses' stamps if they have them.
std::vector<double> read_scan_times(const std::string& times, const std::vector<std::string>& files,
                                    const std::string& poses, const std::vector<double>& pose_stamps) {
  std::vector<double> scan_times = read_times(times);
  if (scan_times.size() != files.size())
    throw input_error(times, 0,
                      "has " + std::to_string(scan_times.size()) + " times for " +
                          std::to_string(files.size()) + " scans" +
                          first_beyond(files, scan_times.size(), "time"));
  if (!pose_stamps.empty()) check_stamps_agree(poses, pose_stamps, times, scan_times);
  return scan_times;
}

// The poses' stamps as the scans' times: they may not go backwards.
std::vector<double> times_of_stamps(const std::string& poses, const std::vector<double>& pose_stamps) {
  for (std::size_t i = 1; i < pose_stamps.size(); ++i)
    if (pose_stamps[i] < pose_stamps[i - 1])
      throw input_error(poses, static_cast<int>(i) + 1, "times go backwards");
  return pose_stamps;
}

// `n` times one scan period apart, from 0.
std::vector<double> periodic_times(const std::string& name, std::size_t n, double scan_period) {
  if (!(scan_period > 0.0)) throw input_error(name, 0, "scan period must be positive");
  std::vector<double> times;
  for (std::size_t i = 0; i < n; ++i) times.push_back(static_cast<double>(i) * scan_period);
  return times;
}

}  // namespace

ScanFolderReader::ScanFolderReader(const ScanFolderOptions& options) {
  // The scans.
  if (!options.scans.empty()) {
    name_ = options.scans;
    files_ = glob_files(options.scans);
    if (files_.empty()) throw input_error(options.scans, 0, "no scan file matches");
  } else {
    name_ = options.folder;
    files_ = scans_in_folder(options.folder);
  }
  pcd_ = scans_are_pcd(files_);
  const fs::path scan_dir = fs::path(files_.front()).parent_path();
  const std::vector<fs::path> beside = {scan_dir, scan_dir.parent_path()};
  const std::size_t n = files_.size();

  // The poses.
  const std::string poses =
      options.poses.empty() ? find_beside(beside, {"poses.txt", "odom.txt"}) : options.poses;
  const std::vector<double> pose_stamps =
      read_poses(poses, pose_format(poses, options.pose_format), info_.odometry);
  if (!poses.empty() && info_.odometry.size() != n)
    throw input_error(poses, 0,
                      "has " + std::to_string(info_.odometry.size()) + " poses for " + std::to_string(n) +
                          " scans (one pose per scan, in scan order)" +
                          first_beyond(files_, info_.odometry.size(), "pose"));

  // The times.
  const std::string times = options.times.empty() ? find_beside(beside, {"times.txt"}) : options.times;
  if (!times.empty())
    info_.times = read_scan_times(times, files_, poses, pose_stamps);
  else if (!pose_stamps.empty())
    info_.times = times_of_stamps(poses, pose_stamps);
  else
    info_.times = periodic_times(name_, n, options.scan_period);
}

PointCloud ScanFolderReader::scan(std::size_t index) const {
  const std::string& file = files_.at(index);
  return pcd_ ? read_pcd(file) : read_kitti_bin(file);
}

}  // namespace tsgraphs::io
