// Bag reading speed: each bag given (a ROS1 .bag, or a rosbag2 folder, .db3 or .mcap) opened
// as `run --bag` opens it (every cloud's header read for its stamp, the odometry decoded), then
// every scan read and decoded, on one thread. Prints the file's size, the time to open, to read
// the scans, MB/s over both and scans/s. With --from SEQ_DIR --to DIR it first writes SEQ_DIR as
// a bag in each format and compression into DIR (kept for later runs) and reads those.
//   ./build/bench/bench_bag_read BAG... [--points-topic /points --odom-topic /odom]
//   ./build/bench/bench_bag_read --from SEQ_DIR --to DIR      (bench/bench_bags.sh)
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/ros1_bag/ros_bag.hpp"
#include "tsgraphs/ros2_bag/rosbag2.hpp"
#include "tsgraphs/io/sequence_folder.hpp"

using namespace tsgraphs;

namespace {

std::uintmax_t size_of(const std::string& path) {
  namespace fs = std::filesystem;
  if (!fs::is_directory(path)) return fs::file_size(path);
  std::uintmax_t n = 0;
  for (const auto& e : fs::recursive_directory_iterator(path))
    if (e.is_regular_file()) n += e.file_size();
  return n;
}

}  // namespace

int main(int argc, char** argv) {
  io::BagOptions options;
  options.points_topic = "/points";
  options.odom_topic = "/odom";
  std::vector<std::string> bags;
  std::string from, to;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--points-topic" && i + 1 < argc)
      options.points_topic = argv[++i];
    else if (a == "--odom-topic" && i + 1 < argc)
      options.odom_topic = argv[++i];
    else if (a == "--from" && i + 1 < argc)
      from = argv[++i];
    else if (a == "--to" && i + 1 < argc)
      to = argv[++i];
    else
      bags.push_back(a);
  }
  if (!from.empty()) {
    std::filesystem::create_directories(to);
    const io::SequenceReader seq(from);
    const Pose3 mount = Pose3::Identity();
    const auto out = [&](const std::string& name) {
      bags.push_back(to + "/" + name);
      return !std::filesystem::exists(bags.back());
    };
    for (const auto& [name, c] : {std::pair{"ros1_none.bag", ros1_bag::BagCompression::none},
                                  std::pair{"ros1_lz4.bag", ros1_bag::BagCompression::lz4},
                                  std::pair{"ros1_bz2.bag", ros1_bag::BagCompression::bz2}})
      if (out(name)) ros1_bag::write_bag(seq, bags.back(), c, mount);
    if (out("ros2_sqlite.db3"))
      ros2_bag::write_rosbag2(seq, bags.back(), ros2_bag::Rosbag2Storage::sqlite, mcap::Compression::none,
                              mount);
    for (const auto& [name, c] : {std::pair{"ros2_mcap_none.mcap", mcap::Compression::none},
                                  std::pair{"ros2_mcap_lz4.mcap", mcap::Compression::lz4},
                                  std::pair{"ros2_mcap_zstd.mcap", mcap::Compression::zstd}})
      if (out(name)) ros2_bag::write_rosbag2(seq, bags.back(), ros2_bag::Rosbag2Storage::mcap, c, mount);
  }
  std::printf("%-28s %9s %8s %8s %8s %9s\n", "bag", "MB", "open s", "read s", "MB/s", "scans/s");
  for (const std::string& bag : bags) {
    options.bag = bag;
    try {
      const auto t0 = std::chrono::steady_clock::now();
      std::unique_ptr<io::ScanSequence> seq;
      if (ros2_bag::is_rosbag2(bag))
        seq = std::make_unique<ros2_bag::Rosbag2Sequence>(options);
      else
        seq = std::make_unique<ros1_bag::BagSequence>(options);
      const auto t1 = std::chrono::steady_clock::now();
      std::size_t points = 0;
      for (std::size_t i = 0; i < seq->size(); ++i) points += seq->scan(i).size();
      const auto t2 = std::chrono::steady_clock::now();
      const double open = std::chrono::duration<double>(t1 - t0).count(),
                   read = std::chrono::duration<double>(t2 - t1).count();
      const double mb = static_cast<double>(size_of(bag)) / 1e6;
      std::printf("%-28s %9.1f %8.2f %8.2f %8.0f %9.0f\n", std::filesystem::path(bag).filename().c_str(), mb,
                  open, read, mb / (open + read), static_cast<double>(seq->size()) / (open + read));
      if (points == 0) std::fprintf(stderr, "%s: no points read\n", bag.c_str());
    } catch (const InputError& e) {
      std::fprintf(stderr, "%s\n", e.what());
      return 2;
    }
  }
  return 0;
}
