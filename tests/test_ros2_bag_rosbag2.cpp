// rosbag2 recordings (ros2_bag/rosbag2.hpp): a small sequence written as SQLite and MCAP files and
// read back, also under rosbag2's own compression, and what a user gets for a topic that is
// missing, of another type or of another definition, a damaged SQLite file, a compressed file cut
// short, and bag folders that are not whole.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "test_support.hpp"
#include "tsgraphs/core/error.hpp"
#include "tsgraphs/mcap/mcap.hpp"
#include "tsgraphs/ros2_bag/ros2_messages.hpp"
#include "tsgraphs/ros2_bag/rosbag2.hpp"

namespace fs = std::filesystem;
using namespace tsgraphs;
using ::testing::HasSubstr;
using ::testing::StartsWith;

namespace {

/// Five scans of a few points, 0.1 s apart from `start` (s), the sensor moving along x.
class FiveScans : public io::ScanSequence {
 public:
  explicit FiveScans(double start = 100.0) {
    for (int i = 0; i < 5; ++i) {
      info_.times.push_back(start + 0.1 * i);
      Pose3 p = Pose3::Identity();
      p.translation() = Eigen::Vector3d(0.2 * i, 0, 1);
      info_.odometry.push_back(p);
    }
  }
  std::size_t size() const override { return info_.times.size(); }
  const io::SequenceInfo& info() const override { return info_; }
  const std::string& dir() const override { return name_; }
  PointCloud scan(std::size_t index) const override {
    PointCloud c;
    for (int k = 0; k < 10; ++k) {
      c.points.emplace_back(1.0f + k, static_cast<float>(index), 0.5f);
      c.intensity.push_back(static_cast<float>(k));
    }
    return c;
  }

 private:
  io::SequenceInfo info_;
  std::string name_ = "five";
};

class Rosbag2 : public test::TempDirTest {
 protected:
  std::string write(const std::string& name, ros2_bag::Rosbag2Storage storage,
                    ros2_bag::Rosbag2Compression compression = ros2_bag::Rosbag2Compression::none,
                    double start = 100.0) const {
    const std::string path = (dir_ / name).string();
    ros2_bag::write_rosbag2(FiveScans(start), path, storage, mcap::Compression::zstd, Pose3::Identity(),
                            compression);
    return path;
  }
  static io::BagOptions options(const std::string& bag, const std::string& odom = "/odom") {
    io::BagOptions o;
    o.bag = bag;
    o.points_topic = "/points";
    o.odom_topic = odom;
    return o;
  }
  static std::string error_of(const io::BagOptions& o) {
    try {
      const ros2_bag::Rosbag2Sequence s(o);
      for (std::size_t i = 0; i < s.size(); ++i) s.scan(i);
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }
};

}  // namespace

TEST_F(Rosbag2, BothStoragesReadBackTheSequence) {
  const FiveScans five;
  for (const auto storage : {ros2_bag::Rosbag2Storage::sqlite, ros2_bag::Rosbag2Storage::mcap}) {
    const std::string path =
        write(storage == ros2_bag::Rosbag2Storage::sqlite ? "five.db3" : "five.mcap", storage);
    EXPECT_TRUE(ros2_bag::is_rosbag2(path));
    const ros2_bag::Rosbag2Sequence s(options(path));
    ASSERT_EQ(s.size(), 5u);
    EXPECT_TRUE(s.sensor_to_base_known());
    for (std::size_t i = 0; i < 5; ++i) {
      EXPECT_EQ(s.info().times[i], five.info().times[i]);
      EXPECT_TRUE(s.info().odometry[i].isApprox(five.info().odometry[i], 1e-12));
      const PointCloud c = s.scan(i);
      ASSERT_EQ(c.size(), 10u);
      EXPECT_EQ(c.points[3], five.scan(i).points[3]);
    }
    EXPECT_THAT(
        ros2_bag::rosbag2_info(path),
        HasSubstr("/points                  sensor_msgs/msg/PointCloud2             5 msgs     10.00 Hz"));
  }
  // A bag folder: metadata.yaml (rosbag2's BagMetadata) naming its one file, with the counts.
  write("folder", ros2_bag::Rosbag2Storage::mcap);
  const YAML::Node meta =
      YAML::LoadFile((dir_ / "folder" / "metadata.yaml").string())["rosbag2_bagfile_information"];
  EXPECT_EQ(meta["storage_identifier"].as<std::string>(), "mcap");
  EXPECT_EQ(meta["relative_file_paths"][0].as<std::string>(), "folder_0.mcap");
  EXPECT_EQ(meta["message_count"].as<int>(), 5 + 5 + 1);
  EXPECT_EQ(meta["topics_with_message_count"][0]["topic_metadata"]["type"].as<std::string>(),
            "sensor_msgs/msg/PointCloud2");
  EXPECT_EQ(meta["duration"]["nanoseconds"].as<std::uint64_t>(), 400000000u);
  EXPECT_EQ(ros2_bag::Rosbag2Sequence(options((dir_ / "folder").string())).size(), 5u);
  // A bag folder is not written over.
  EXPECT_THROW(write("folder", ros2_bag::Rosbag2Storage::sqlite), InputError);
  EXPECT_FALSE(ros2_bag::is_rosbag2((dir_ / "none.db3").string()));
  std::ofstream(dir_ / "text.db3") << "not a database";
  EXPECT_FALSE(ros2_bag::is_rosbag2((dir_ / "text.db3").string()));
}

TEST_F(Rosbag2, TopicsMissingOrOfAnotherTypeOrDefinitionAreNamed) {
  const std::string path = write("five.mcap", ros2_bag::Rosbag2Storage::mcap);
  EXPECT_EQ(error_of(options(path, "/nope")), path + ": no topic /nope (topics: /odom, /points, /tf_static)");
  EXPECT_EQ(error_of(options(path, "/points")), path +
                                                    ": /points is sensor_msgs/msg/PointCloud2, expected "
                                                    "nav_msgs/msg/Odometry or geometry_msgs/msg/PoseStamped");
  // A topic named PointCloud2 whose recorded definition is another message's.
  const std::string other = (dir_ / "other.mcap").string();
  {
    mcap::Writer w(other, {"ros2", "test", mcap::Compression::none, 1 << 20});
    const auto schema = w.add_schema(ros2_bag::ros2::kPointCloud2, "ros2msg",
                                     ros2_bag::ros2::definition(ros2_bag::ros2::kPoseStamped));
    w.write(w.add_channel(schema, "/points", "cdr"), 1, 1,
            ros2_bag::ros2::encode_pose_stamped({1.0, "map", "", Pose3::Identity()}));
    w.finish();
  }
  io::BagOptions o = options(other, "");
  EXPECT_THAT(
      error_of(o),
      AllOf(StartsWith(
          other +
          ": /points (sensor_msgs/msg/PointCloud2): its definition declares (Header header, Pose pose)")));
}

TEST_F(Rosbag2, DamagedFilesAndIncompleteFoldersAreNamed) {
  const std::string db = write("five.db3", ros2_bag::Rosbag2Storage::sqlite);
  std::string bytes;
  {
    std::ifstream in(db, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  const std::string cut = (dir_ / "cut.db3").string();
  std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  EXPECT_THAT(error_of(options(cut)), StartsWith(cut + ": "));
  // Folders: no metadata.yaml is no rosbag2 bag; one naming a file it lacks, or compressed.
  fs::create_directories(dir_ / "bag");
  EXPECT_FALSE(ros2_bag::is_rosbag2((dir_ / "bag").string()));
  const std::string metadata = (dir_ / "bag" / "metadata.yaml").string();
  std::ofstream(metadata) << "rosbag2_bagfile_information:\n  relative_file_paths: [bag_0.db3]\n";
  EXPECT_TRUE(ros2_bag::is_rosbag2((dir_ / "bag").string()));
  EXPECT_EQ(error_of(options((dir_ / "bag").string())),
            metadata + ":2: lists bag_0.db3, which is not in the folder");
  // rosbag2 compresses with zstd only; a mode it does not have is named with its line.
  std::ofstream(metadata) << "rosbag2_bagfile_information:\n  relative_file_paths: [bag_0.db3]\n"
                             "  compression_format: lz4\n  compression_mode: FILE\n";
  EXPECT_EQ(error_of(options((dir_ / "bag").string())),
            metadata + ":3: compression_format 'lz4': only zstd, rosbag2's own compressor, is read");
  std::ofstream(metadata) << "rosbag2_bagfile_information:\n  relative_file_paths: [bag_0.db3]\n"
                             "  compression_format: zstd\n  compression_mode: CHUNK\n";
  EXPECT_EQ(error_of(options((dir_ / "bag").string())),
            metadata + ":4: compression_mode CHUNK: expected FILE, MESSAGE or none");
  std::ofstream(metadata) << "rosbag2_bagfile_information: [\n";
  EXPECT_THAT(error_of(options((dir_ / "bag").string())), StartsWith(metadata + ":"));
}

// Issue 52: a folder whose metadata.yaml listed its file twice was read twice (42 scans from
// 21, time going back). A file listed again, under any spelling, is refused naming the line.
TEST_F(Rosbag2, AFileListedTwiceInMetadataIsRefusedNamingTheRepeat) {
  write("folder", ros2_bag::Rosbag2Storage::sqlite);
  const fs::path folder = dir_ / "folder";
  const std::string metadata = (folder / "metadata.yaml").string();
  const auto listing = [&](const std::string& files) {
    std::ofstream(metadata) << "rosbag2_bagfile_information:\n  relative_file_paths:\n" << files;
    return error_of(options(folder.string()));
  };
  EXPECT_EQ(listing("    - folder_0.db3\n"), "");
  EXPECT_EQ(ros2_bag::read_rosbag2_metadata(folder.string()).files,
            std::vector<std::string>{(folder / "folder_0.db3").string()});
  EXPECT_EQ(listing("    - folder_0.db3\n    - folder_0.db3\n"),
            metadata + ":4: lists folder_0.db3 again (as folder_0.db3 on line 3): each file is read once");
  EXPECT_EQ(listing("    - ./folder_0.db3\n    - folder_0.db3\n"),
            metadata + ":4: lists folder_0.db3 again (as ./folder_0.db3 on line 3): each file is read once");
  EXPECT_EQ(
      listing("    - folder_0.db3\n    - ../folder/./folder_0.db3\n"),
      metadata +
          ":4: lists ../folder/./folder_0.db3 again (as folder_0.db3 on line 3): each file is read once");
  fs::create_symlink("folder_0.db3", folder / "link.db3");
  EXPECT_EQ(listing("    - link.db3\n    - folder_0.db3\n"),
            metadata + ":4: lists folder_0.db3 again (as link.db3 on line 3): each file is read once");
  // bag-info reads the same list.
  EXPECT_EQ(test::input_error_of([&] { ros2_bag::rosbag2_info(folder.string()); }),
            metadata + ":4: lists folder_0.db3 again (as link.db3 on line 3): each file is read once");
  // A name outside the bag folder (absolute, or climbing out of it) would read a file elsewhere.
  const std::string absolute = listing("    - " + (folder / "folder_0.db3").string() + "\n");
  EXPECT_EQ(absolute.rfind(metadata + ":3: lists /", 0), 0u) << absolute;
  EXPECT_NE(absolute.find(", an absolute path: files are named from the bag folder"), std::string::npos)
      << absolute;
  fs::copy_file(folder / "folder_0.db3", dir_ / "outside.db3");
  EXPECT_EQ(listing("    - ../outside.db3\n"),
            metadata + ":3: lists ../outside.db3, which is not inside the bag folder");
  // An entry that is no file name is named too, not an internal error; a name's bytes are quoted printable.
  EXPECT_EQ(listing("    - {path: folder_0.db3}\n"),
            metadata + ":3: relative_file_paths: an entry that is not a file name");
  EXPECT_EQ(listing("    - \"a\\x1b[2J.db3\"\n"),
            metadata + ":3: lists a\\x1b[2J.db3, which is not in the folder");
  std::ofstream(metadata) << "rosbag2_bagfile_information: [1, 2]\n";
  EXPECT_EQ(error_of(options(folder.string())),
            metadata + ": no rosbag2_bagfile_information.relative_file_paths");
}

// Issue 52: a split whose second file was a byte copy of the first (another name, the same
// messages) was read twice, time going back. A file whose first message comes before the last
// of the file before it is refused naming both: by metadata.yaml's `files` times before any file
// is opened, else by the files' own times as they are opened. A split in time order reads whole.
TEST_F(Rosbag2, ASplitFileStartingBeforeTheLastOfThePreviousIsRefused) {
  for (const auto storage : {ros2_bag::Rosbag2Storage::sqlite, ros2_bag::Rosbag2Storage::mcap}) {
    const std::string ext = storage == ros2_bag::Rosbag2Storage::sqlite ? ".db3" : ".mcap";
    SCOPED_TRACE(ext);
    const fs::path split = dir_ / ("split" + ext);
    fs::create_directories(split);
    fs::copy_file(fs::path(write("first" + ext + "_bag", storage)) / ("first" + ext + "_bag_0" + ext),
                  split / ("split_0" + ext));
    const std::string later =
        write("later" + ext + "_bag", storage, ros2_bag::Rosbag2Compression::none, 101.0);
    fs::copy_file(fs::path(later) / ("later" + ext + "_bag_0" + ext), split / ("split_1" + ext));
    const std::string metadata = (split / "metadata.yaml").string();
    std::ofstream(metadata) << "rosbag2_bagfile_information:\n  relative_file_paths: [split_0" << ext
                            << ", split_1" << ext << "]\n";
    EXPECT_EQ(ros2_bag::Rosbag2Sequence(options(split.string())).size(), 10u);

    fs::copy_file(split / ("split_0" + ext), split / ("split_1" + ext), fs::copy_options::overwrite_existing);
    const std::string repeated = metadata + ": split_1" + ext +
                                 ": its first message (t 100.000000000 s) is before the last of split_0" +
                                 ext + " (t 100.400000000 s): a file repeated?";
    EXPECT_EQ(error_of(options(split.string())), repeated);
    EXPECT_EQ(test::input_error_of([&] { ros2_bag::rosbag2_info(split.string()); }), repeated);
  }
  // metadata.yaml's times (rosbag2 >= Humble): refused at the later file's entry, unopened.
  const fs::path split = dir_ / "split.db3";
  std::ofstream(split / "split_1.db3") << "not opened";
  const auto file_entry = [](const std::string& name, const std::string& start) {
    return "    - path: " + name + "\n      starting_time:\n        nanoseconds_since_epoch: " + start +
           "\n      duration:\n        nanoseconds: 400000000\n      message_count: 11\n";
  };
  const std::string metadata = (split / "metadata.yaml").string();
  std::ofstream(metadata)
      << "rosbag2_bagfile_information:\n  relative_file_paths: [split_0.db3, split_1.db3]\n  files:\n"
      << file_entry("split_0.db3", "100000000000") << file_entry("split_1.db3", "100000000000");
  EXPECT_EQ(test::input_error_of([&] { ros2_bag::read_rosbag2_metadata(split.string()); }),
            metadata +
                ":10: split_1.db3: its first message (t 100.000000000 s) is before the last of split_0.db3 "
                "(t 100.400000000 s): a file repeated?");
  // Times that follow pass the metadata, and the file is read (here: not a bag).
  std::ofstream(metadata)
      << "rosbag2_bagfile_information:\n  relative_file_paths: [split_0.db3, split_1.db3]\n  files:\n"
      << file_entry("split_0.db3", "100000000000") << file_entry("split_1.db3", "100400000000");
  EXPECT_EQ(error_of(options(split.string())),
            (split / "split_1.db3").string() + ": neither an SQLite (.db3) nor an MCAP file");
}

// rosbag2's own compression (`ros2 bag record --compression-mode file|message`, zstd): each
// storage file compressed whole, or each message's data. Both storages read back the same
// scans and odometry as the uncompressed bag, and a file decompressed to read it is not left
// behind in the temporary folder.
TEST_F(Rosbag2, RosbagsOwnCompressionReadsBackTheSequence) {
  const fs::path tmp = dir_ / "tmp";
  fs::create_directories(tmp);
  const char* old_tmpdir = std::getenv("TMPDIR");
  const std::string kept_tmpdir = old_tmpdir ? old_tmpdir : "";
  setenv("TMPDIR", tmp.c_str(), 1);
  const FiveScans five;
  for (const auto storage : {ros2_bag::Rosbag2Storage::sqlite, ros2_bag::Rosbag2Storage::mcap}) {
    const std::string ext = storage == ros2_bag::Rosbag2Storage::sqlite ? ".db3" : ".mcap";
    for (const auto mode : {ros2_bag::Rosbag2Compression::file, ros2_bag::Rosbag2Compression::message}) {
      const bool file_mode = mode == ros2_bag::Rosbag2Compression::file;
      const std::string name =
          std::string(file_mode ? "file" : "message") + (ext == ".db3" ? "_sqlite" : "_mcap");
      SCOPED_TRACE(name);
      const std::string path = write(name, storage, mode);
      const YAML::Node meta =
          YAML::LoadFile((fs::path(path) / "metadata.yaml").string())["rosbag2_bagfile_information"];
      EXPECT_EQ(meta["compression_format"].as<std::string>(), "zstd");
      EXPECT_EQ(meta["compression_mode"].as<std::string>(), file_mode ? "FILE" : "MESSAGE");
      const std::string listed = name + "_0" + ext + (file_mode ? ".zstd" : "");
      EXPECT_EQ(meta["relative_file_paths"][0].as<std::string>(), listed);
      EXPECT_TRUE(fs::is_regular_file(fs::path(path) / listed));
      EXPECT_EQ(std::distance(fs::directory_iterator(path), fs::directory_iterator()),
                2);  // and metadata.yaml

      const ros2_bag::Rosbag2Sequence s(options(path));
      ASSERT_EQ(s.size(), 5u);
      for (std::size_t i = 0; i < s.size(); ++i) {
        EXPECT_DOUBLE_EQ(s.info().times[i], five.info().times[i]);
        EXPECT_TRUE(s.info().odometry[i].isApprox(five.info().odometry[i], 1e-12));
        const PointCloud got = s.scan(i), want = five.scan(i);
        ASSERT_EQ(got.size(), want.size());
        for (std::size_t k = 0; k < got.size(); ++k) EXPECT_EQ(got.points[k], want.points[k]);
      }
      EXPECT_THAT(ros2_bag::rosbag2_info(path),
                  HasSubstr("/points                  sensor_msgs/msg/PointCloud2             5 msgs"));
      EXPECT_TRUE(fs::is_empty(tmp)) << "a decompressed file was left in TMPDIR";
    }
  }
  // Only a folder records the compression: a single file is refused before anything is written.
  EXPECT_THROW(write("one.db3", ros2_bag::Rosbag2Storage::sqlite, ros2_bag::Rosbag2Compression::message),
               InputError);
  EXPECT_FALSE(fs::exists(dir_ / "one.db3"));

  // A compressed file cut short names the file; still nothing left in TMPDIR.
  const fs::path cut = dir_ / "file_sqlite" / "file_sqlite_0.db3.zstd";
  fs::resize_file(cut, fs::file_size(cut) / 2);
  EXPECT_THAT(error_of(options((dir_ / "file_sqlite").string())),
              StartsWith(cut.string() + ": zstd data that "));
  EXPECT_TRUE(fs::is_empty(tmp));
  if (old_tmpdir) {
    setenv("TMPDIR", kept_tmpdir.c_str(), 1);
  } else {
    unsetenv("TMPDIR");
  }
}
