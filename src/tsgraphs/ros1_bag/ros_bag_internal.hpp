#pragma once
/// What the ROS 1 bag files share (ros_bag_check, _reader, _info and _writer.cpp, the only files of
/// tsgraphs that see ROS types): the structure check run before rosbag reads a byte, and rosbag's
/// log lines gathered as ours.
#include <console_bridge/console.h>

#include <cstdint>
#include <cstdio>
#include <mutex>
#include <string>
#include <vector>

namespace tsgraphs::ros1_bag::ros_bag_internal {

constexpr const char* kTfStaticTopic = "/tf_static";
constexpr std::uint64_t kLengthBytes = 4;  // every length word of the bag format

/// The little-endian number of `bytes` (at most 8).
std::uint64_t little_endian(const std::string& bytes);

/// What the reads after the check may rely on.
struct BagLimits {
  std::uint64_t largest_chunk = 0;  ///< no message can be longer
};

/// Walks every record of the bag at `path` (and every record inside its uncompressed chunks) and
/// throws an InputError "bag: byte N: what" at the first length, count or offset that does not fit.
BagLimits check_bag(const std::string& path);

/// Whether `path` is a regular file; a symlink loop or an unreadable path is an InputError.
bool is_bag_file(const std::string& path);

/// rosbag's own log lines (console_bridge) gathered instead of printed on stderr, so they
/// reach the user as part of our messages: an error's text, or the sequence's warnings. A
/// reading operation collects the lines of its thread while a RosbagLines is alive.
class RosbagLines {
 public:
  RosbagLines() {
    static std::once_flag once;
    std::call_once(once, [] {
      static Forwarder forwarder;
      console_bridge::useOutputHandler(&forwarder);
      console_bridge::setLogLevel(console_bridge::CONSOLE_BRIDGE_LOG_WARN);
    });
    previous_ = sink_;
    sink_ = &lines_;
  }
  ~RosbagLines() { sink_ = previous_; }
  RosbagLines(const RosbagLines&) = delete;
  RosbagLines& operator=(const RosbagLines&) = delete;
  const std::vector<std::string>& lines() const { return lines_; }
  /// " (rosbag: last line)" for an error's text, "" when rosbag said nothing.
  std::string last() const { return lines_.empty() ? "" : " (rosbag: " + lines_.back() + ")"; }

 private:
  /// The handler console_bridge calls, from the logging thread.
  struct Forwarder : console_bridge::OutputHandler {
    void log(const std::string& text, console_bridge::LogLevel, const char*, int) override {
      if (sink_ != nullptr) {
        sink_->push_back(text);
      } else {  // outside any reading operation (not expected): still one line of ours
        std::fprintf(stderr, "tsgraphs: rosbag: %s\n", text.c_str());
      }
    }
  };
  static inline thread_local std::vector<std::string>* sink_ = nullptr;
  std::vector<std::string>* previous_ = nullptr;
  std::vector<std::string> lines_;
};

}  // namespace tsgraphs::ros1_bag::ros_bag_internal
