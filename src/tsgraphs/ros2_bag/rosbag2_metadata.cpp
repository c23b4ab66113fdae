// A rosbag2 bag folder's metadata.yaml read: its files, in order, and rosbag2's own compression.
#include "tsgraphs/ros2_bag/rosbag2.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/core/printable.hpp"
#include "tsgraphs/ros2_bag/rosbag2_internal.hpp"

namespace tsgraphs::ros2_bag {

using namespace rosbag2_internal;

namespace {

namespace fs = std::filesystem;

/// rosbag2's own compression of a recording, as metadata.yaml states it (file:line naming it).
Rosbag2Compression compression_of(const YAML::Node& info, const std::string& metadata) {
  const auto scalar = [&](const char* key) {
    const YAML::Node n = info[key];
    return std::make_pair(n && n.IsScalar() ? n.as<std::string>() : std::string(), n ? n.Mark().line + 1 : 0);
  };
  const auto [written, mode_line] = scalar("compression_mode");
  std::string mode = written;  // rosbag2 writes FILE and MESSAGE; its reader takes any case
  std::transform(mode.begin(), mode.end(), mode.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  Rosbag2Compression out;
  if (mode.empty() || mode == "none") return Rosbag2Compression::none;
  if (mode == "file") {
    out = Rosbag2Compression::file;
  } else if (mode == "message") {
    out = Rosbag2Compression::message;
  } else {
    throw input_error(metadata, mode_line,
                      "compression_mode " + printable(written) + ": expected FILE, MESSAGE or none");
  }
  if (const auto [format, line] = scalar("compression_format"); format != "zstd") {
    throw input_error(
        metadata, line,
        "compression_format '" + printable(format) + "': only zstd, rosbag2's own compressor, is read");
  }
  return out;
}

/// metadata.yaml's rosbag2_bagfile_information, a map, or an InputError naming the file.
YAML::Node bagfile_information(const std::string& metadata) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(metadata);
  } catch (const YAML::Exception& e) {  // its message quotes the byte it stumbled on, raw
    throw input_error(metadata, e.mark.line + 1, "not YAML: " + printable(e.msg, e.msg.size()));
  }
  const YAML::Node info = root.IsMap() ? root["rosbag2_bagfile_information"] : YAML::Node();
  if (!info || !info.IsMap() || !info["relative_file_paths"] || !info["relative_file_paths"].IsSequence()) {
    throw input_error(metadata, 0, "no rosbag2_bagfile_information.relative_file_paths");
  }
  return info;
}

/// The file `entry` of relative_file_paths names in `folder`: a file there, listed once. The same
/// file under another spelling (./a.db3 and a.db3, a link to it) is a repeat too: read twice, its
/// scans would come twice and time would go back. `listed` holds the files so far, by their
/// canonical path, with the line that listed each.
std::string listed_file(const YAML::Node& entry, const std::string& folder, const std::string& metadata,
                        std::map<fs::path, std::pair<std::string, int>>& listed) {
  const int line = entry.Mark().line + 1;
  if (!entry.IsScalar())
    throw input_error(metadata, line, "relative_file_paths: an entry that is not a file name");
  const std::string name = entry.Scalar();
  // rosbag2 names files relative to the bag folder; an absolute name or one climbing out of it
  // would read a file elsewhere.
  const fs::path home = fs::absolute(folder).lexically_normal();
  const fs::path relative = (home / name).lexically_normal().lexically_relative(home);
  if (fs::path(name).is_absolute())
    throw input_error(metadata, line,
                      "lists " + printable(name) + ", an absolute path: files are named from the bag folder");
  if (relative.empty() || *relative.begin() == "..")
    throw input_error(metadata, line, "lists " + printable(name) + ", which is not inside the bag folder");
  const std::string file = (fs::path(folder) / name).string();
  std::error_code ec;
  if (!fs::is_regular_file(file, ec))
    throw input_error(metadata, line, "lists " + printable(name) + ", which is not in the folder");
  const fs::path canonical = fs::canonical(file, ec);
  if (ec)
    throw input_error(metadata, line, "lists " + printable(name) + ", which cannot be read: " + ec.message());
  const auto [first, fresh] = listed.emplace(canonical, std::make_pair(name, line));
  if (!fresh) {
    throw input_error(metadata, line,
                      "lists " + printable(name) + " again (as " + printable(first->second.first) +
                          " on line " + std::to_string(first->second.second) + "): each file is read once");
  }
  return file;
}

/// A time in ns as seconds to the nanosecond, for messages.
std::string seconds(std::uint64_t ns) {
  constexpr std::uint64_t kNsPerSecond = 1000000000;
  char text[48];
  std::snprintf(text, sizeof text, "%llu.%09llu s", static_cast<unsigned long long>(ns / kNsPerSecond),
                static_cast<unsigned long long>(ns % kNsPerSecond));
  return text;
}

/// The span metadata.yaml's `files` section gives a file (rosbag2 from Humble on writes each
/// file's path, starting_time and duration there), by the name it lists, with the entry's line.
/// An entry without readable times gives none: that file is checked once it is read.
std::map<std::string, std::pair<TimeSpan, int>> listed_spans(const YAML::Node& info) {
  std::map<std::string, std::pair<TimeSpan, int>> out;
  const YAML::Node files = info["files"];
  if (!files || !files.IsSequence()) return out;
  for (const YAML::Node& f : files) {
    try {
      const std::string path = f["path"].as<std::string>();
      const auto start = f["starting_time"]["nanoseconds_since_epoch"].as<std::uint64_t>();
      const auto duration = f["duration"]["nanoseconds"].as<std::uint64_t>();
      if (duration > std::numeric_limits<std::uint64_t>::max() - start) continue;  // no time of a message
      out.emplace(path, std::make_pair(TimeSpan{start, start + duration}, f.Mark().line + 1));
    } catch (const YAML::Exception&) {
      continue;  // not a file's times as rosbag2 writes them: read the file instead
    }
  }
  return out;
}

/// Split files in time order, as far as metadata.yaml gives their times: a repeat is refused
/// before any file is opened (a FILE-compressed one decompressed).
void check_listed_order(const YAML::Node& info, const Rosbag2Metadata& listed, const std::string& metadata) {
  const std::map<std::string, std::pair<TimeSpan, int>> spans = listed_spans(info);
  for (std::size_t i = 1; i < listed.names.size(); ++i) {
    const auto previous = spans.find(listed.names[i - 1]), span = spans.find(listed.names[i]);
    if (previous == spans.end() || span == spans.end()) continue;
    check_follows(metadata, span->second.second, listed.names[i], span->second.first, listed.names[i - 1],
                  previous->second.first);
  }
}

}  // namespace

namespace rosbag2_internal {

void check_follows(const std::string& metadata, int line, const std::string& file, const TimeSpan& span,
                   const std::string& previous_file, const TimeSpan& previous) {
  if (span.first >= previous.last) return;
  throw input_error(metadata, line,
                    printable(file) + ": its first message (t " + seconds(span.first) +
                        ") is before the last of " + printable(previous_file) + " (t " +
                        seconds(previous.last) + "): a file repeated?");
}

}  // namespace rosbag2_internal

Rosbag2Metadata read_rosbag2_metadata(const std::string& folder) {
  const std::string metadata = (fs::path(folder) / kMetadataFile).string();
  std::error_code ec;
  if (!fs::is_regular_file(metadata, ec))
    throw input_error(folder, 0, "a folder without metadata.yaml: not a rosbag2 bag");
  const YAML::Node info = bagfile_information(metadata);
  Rosbag2Metadata out;
  out.compression = compression_of(info, metadata);
  std::map<fs::path, std::pair<std::string, int>> listed;
  for (const YAML::Node& entry : info["relative_file_paths"]) {
    out.files.push_back(listed_file(entry, folder, metadata, listed));
    out.names.push_back(entry.Scalar());
  }
  if (out.files.empty()) throw input_error(metadata, 0, "lists no files");
  check_listed_order(info, out, metadata);
  return out;
}

}  // namespace tsgraphs::ros2_bag
