// The sequence folder: write / commit / read round trip, atomic replacement, and the reader's
// checks of inconsistent folders.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <set>
#include <sstream>
#include <string>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/core/pose.hpp"
#include "tsgraphs/io/sequence_folder.hpp"

#include "test_support.hpp"

using namespace tsgraphs;
using namespace tsgraphs::io;
using ::testing::HasSubstr;
using ::testing::StartsWith;
using tsgraphs::test::input_error_of;
using tsgraphs::test::TempDirTest;

namespace fs = std::filesystem;

namespace {

std::uint32_t bits(float f) {
  std::uint32_t u;
  std::memcpy(&u, &f, sizeof u);
  return u;
}

using test::read_file;

// Writes text to any path (TempDirTest::write_file writes to a name in dir_).
void write_text(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

std::set<std::string> names_in(const fs::path& dir) {
  std::set<std::string> out;
  for (const auto& e : fs::directory_iterator(dir)) out.insert(e.path().filename().string());
  return out;
}

PointCloud random_cloud(std::mt19937& rng, std::size_t n, bool intensity, bool labels) {
  std::uniform_real_distribution<float> u(-50.0f, 50.0f);
  std::uniform_int_distribution<std::uint32_t> label(0, 6);
  PointCloud c;
  for (std::size_t i = 0; i < n; ++i) {
    // one draw per statement, the last argument first: a call's argument order is unspecified (gcc's kept)
    const float z = u(rng), y = u(rng), x = u(rng);
    c.points.emplace_back(x, y, z);
    if (intensity) c.intensity.push_back(u(rng) + 50.0f);
    if (labels) c.labels.push_back(label(rng));
  }
  return c;
}

void expect_pose_near(const Pose3& a, const Pose3& b, double tol = 1e-8) {
  EXPECT_LT((a.translation() - b.translation()).cwiseAbs().maxCoeff(), tol);
  EXPECT_LT((a.linear() - b.linear()).cwiseAbs().maxCoeff(), tol);
}

const char* kSceneYaml = "name: test_scene\nseed: 3\n";

class SequenceFolder : public TempDirTest {
 protected:
  // The sequence goes to dir_/seq, which does not exist yet.
  void SetUp() override {
    TempDirTest::SetUp();
    seq_ = dir_ / "seq";
  }

  // Three scans: the first two with intensity and labels, the third with neither.
  void make_clouds() {
    std::mt19937 rng(99);
    clouds_ = {random_cloud(rng, 50, true, true), random_cloud(rng, 7, true, true),
               random_cloud(rng, 20, false, false)};
    // Values that must survive bit for bit.
    clouds_[0].points[0] = Eigen::Vector3f(-0.0f, 1e-38f, 3.4e38f);
    clouds_[0].intensity[0] = 1.17549435e-38f / 4.0f;  // subnormal
    clouds_[0].points[1] = Eigen::Vector3f(0.1f, -123.456f, 1.0f / 3.0f);
  }

  SequenceInfo make_info(std::size_t n = 3) {
    SequenceInfo info;
    for (std::size_t i = 0; i < n; ++i) {
      info.times.push_back(1000.0 + 0.1 * static_cast<double>(i) + 0.000000123);
      info.odometry.push_back(make_pose(Eigen::Vector3d(0.5 * i, -0.25 * i, 0.01 * i), 0.3 * i, 0.02));
      info.groundtruth.push_back(make_pose(Eigen::Vector3d(0.51 * i, -0.2 * i, 0.0), 0.31 * i));
    }
    info.lap_starts = {info.times.front(), info.times.front() + 0.15};
    info.has_rooms = true;
    info.rooms.push_back({"corridor_south", "L3", {Vec2(0, 0), Vec2(30, 0), Vec2(30, 3), Vec2(0, 3)}, 0.0});
    info.rooms.push_back({"office \"A\"", "L4", {Vec2(0.1, 3), Vec2(5.25, 3), Vec2(5.25, 8.125)}, 3.5});
    info.scene_yaml = kSceneYaml;
    return info;
  }

  void write_sequence(const fs::path& dir, std::size_t n = 3) {
    if (clouds_.empty()) make_clouds();
    SequenceWriter w(dir.string());
    for (std::size_t i = 0; i < n; ++i) w.write_scan(i, clouds_[i % clouds_.size()]);
    w.commit(make_info(n));
  }

  fs::path seq_;
  std::vector<PointCloud> clouds_;
};

}  // namespace

TEST(SequenceFolderNames, ScanStem) {
  EXPECT_EQ(scan_stem(0), "000000");
  EXPECT_EQ(scan_stem(42), "000042");
  EXPECT_EQ(scan_stem(999999), "999999");
  EXPECT_EQ(scan_stem(1234567), "1234567");
}

TEST_F(SequenceFolder, RoundTrip) {
  write_sequence(seq_);
  const SequenceInfo expected = make_info();
  const SequenceReader r(seq_.string());
  ASSERT_EQ(r.size(), 3u);
  EXPECT_EQ(r.dir(), seq_.string());
  const SequenceInfo& info = r.info();

  ASSERT_EQ(info.times.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) EXPECT_NEAR(info.times[i], expected.times[i], 1e-9) << i;
  ASSERT_EQ(info.odometry.size(), 3u);
  ASSERT_EQ(info.groundtruth.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    expect_pose_near(info.odometry[i], expected.odometry[i]);
    expect_pose_near(info.groundtruth[i], expected.groundtruth[i]);
  }
  ASSERT_EQ(info.lap_starts.size(), 2u);
  EXPECT_NEAR(info.lap_starts[0], expected.lap_starts[0], 1e-9);
  EXPECT_NEAR(info.lap_starts[1], expected.lap_starts[1], 1e-9);

  EXPECT_TRUE(info.has_rooms);
  ASSERT_EQ(info.rooms.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(info.rooms[i].name, expected.rooms[i].name);
    EXPECT_EQ(info.rooms[i].level, expected.rooms[i].level);
    EXPECT_EQ(info.rooms[i].elevation, expected.rooms[i].elevation);
    ASSERT_EQ(info.rooms[i].polygon.size(), expected.rooms[i].polygon.size());
    for (std::size_t k = 0; k < expected.rooms[i].polygon.size(); ++k) {
      EXPECT_EQ(info.rooms[i].polygon[k], expected.rooms[i].polygon[k]) << i << " " << k;
    }
  }

  EXPECT_EQ(r.scene_path(), (seq_ / "scene.yaml").string());
  EXPECT_EQ(read_file(r.scene_path()), kSceneYaml);

  for (std::size_t s = 0; s < 3; ++s) {
    const PointCloud& want = clouds_[s];
    const PointCloud got = r.scan(s);
    ASSERT_EQ(got.size(), want.size()) << s;
    ASSERT_TRUE(got.has_intensity()) << s;
    ASSERT_EQ(got.intensity.size(), got.size());
    for (std::size_t i = 0; i < want.size(); ++i) {
      for (int k = 0; k < 3; ++k) {
        ASSERT_EQ(bits(got.points[i][k]), bits(want.points[i][k]))
            << "scan " << s << " point " << i << " axis " << k;
      }
      const float wi = want.has_intensity() ? want.intensity[i] : 0.0f;
      ASSERT_EQ(bits(got.intensity[i]), bits(wi)) << "scan " << s << " point " << i;
    }
    EXPECT_EQ(got.has_labels(), want.has_labels()) << s;
    if (want.has_labels()) {
      EXPECT_EQ(got.labels, want.labels) << s;
    }
  }
}

TEST_F(SequenceFolder, FilesHaveTheNamesOfTheFormat) {
  write_sequence(seq_);
  for (const char* f : {"times.txt", "odom.txt", "groundtruth.txt", "laps.txt", "rooms_gt.json", "scene.yaml",
                        "scans/000000.bin", "scans/000000.label", "scans/000001.bin", "scans/000001.label",
                        "scans/000002.bin"}) {
    EXPECT_TRUE(fs::is_regular_file(seq_ / f)) << f;
  }
  EXPECT_FALSE(fs::exists(seq_ / "scans/000002.label"));  // the third cloud has no labels
  EXPECT_FALSE(fs::exists(seq_ / "scans/000003.bin"));
  // KITTI layout: 4 float32 per point; SemanticKITTI: one uint32 per point.
  EXPECT_EQ(fs::file_size(seq_ / "scans/000000.bin"), 50u * 16u);
  EXPECT_EQ(fs::file_size(seq_ / "scans/000000.label"), 50u * 4u);
  EXPECT_EQ(fs::file_size(seq_ / "scans/000001.bin"), 7u * 16u);
  EXPECT_EQ(fs::file_size(seq_ / "scans/000002.bin"), 20u * 16u);
  // Nothing else is left next to the sequence.
  EXPECT_EQ(names_in(dir_), std::set<std::string>{"seq"});
  // times.txt: one number a line.
  std::istringstream times(read_file(seq_ / "times.txt"));
  std::string line;
  int lines = 0;
  while (std::getline(times, line)) {
    ++lines;
    EXPECT_NEAR(std::stod(line), 1000.0 + 0.1 * (lines - 1) + 0.000000123, 1e-9) << line;
  }
  EXPECT_EQ(lines, 3);
}

TEST_F(SequenceFolder, MinimalSequenceHasNoOptionalFiles) {
  std::mt19937 rng(1);
  {
    SequenceWriter w(seq_.string());
    w.write_scan(0, random_cloud(rng, 3, true, false));
    SequenceInfo info;
    info.times = {0.5};
    info.odometry = {Pose3::Identity()};
    w.commit(info);
  }
  EXPECT_EQ(names_in(seq_), (std::set<std::string>{"scans", "times.txt", "odom.txt"}));
  const SequenceReader r(seq_.string());
  EXPECT_EQ(r.size(), 1u);
  EXPECT_TRUE(r.info().groundtruth.empty());
  EXPECT_TRUE(r.info().lap_starts.empty());
  EXPECT_FALSE(r.info().has_rooms);
  EXPECT_EQ(r.scene_path(), "");
  EXPECT_FALSE(r.scan(0).has_labels());
}

TEST_F(SequenceFolder, EmptyRoomListIsWritten) {
  {
    SequenceWriter w(seq_.string());
    w.write_scan(0, PointCloud());
    SequenceInfo info;
    info.times = {0.0};
    info.odometry = {Pose3::Identity()};
    info.has_rooms = true;  // simulated scene without rooms: the file says "no rooms"
    w.commit(info);
  }
  const SequenceReader r(seq_.string());
  EXPECT_TRUE(r.info().has_rooms);
  EXPECT_TRUE(r.info().rooms.empty());
  EXPECT_EQ(r.scan(0).size(), 0u);
}

TEST_F(SequenceFolder, UncommittedWriterLeavesNothing) {
  make_clouds();
  {
    SequenceWriter w(seq_.string());
    w.write_scan(0, clouds_[0]);
    w.write_scan(1, clouds_[1]);
    EXPECT_FALSE(fs::exists(seq_)) << "the final folder must not appear before commit";
  }
  EXPECT_FALSE(fs::exists(seq_));
  EXPECT_TRUE(names_in(dir_).empty()) << "temporary folder left behind";
}

TEST_F(SequenceFolder, FailedCommitLeavesNothing) {
  make_clouds();
  {
    SequenceWriter w(seq_.string());
    w.write_scan(0, clouds_[0]);
    SequenceInfo info = make_info(2);  // 2 times for 1 scan
    EXPECT_THROW(w.commit(info), std::logic_error);
  }
  EXPECT_FALSE(fs::exists(seq_));
  EXPECT_TRUE(names_in(dir_).empty());
}

TEST_F(SequenceFolder, UncommittedOverwriteKeepsTheEarlierSequence) {
  write_sequence(seq_);
  {
    SequenceWriter w(seq_.string());
    w.write_scan(0, clouds_[2]);
  }
  const SequenceReader r(seq_.string());
  EXPECT_EQ(r.size(), 3u);
  EXPECT_EQ(r.scan(0).size(), 50u);
  EXPECT_EQ(names_in(dir_), std::set<std::string>{"seq"});
}

TEST_F(SequenceFolder, RefusesAFolderThatIsNotASequence) {
  fs::create_directories(seq_);
  write_text(seq_ / "thesis.tex", "precious");
  const std::string msg = input_error_of([&] { SequenceWriter w(seq_.string()); });
  EXPECT_THAT(msg, HasSubstr(seq_.string()));
  EXPECT_EQ(read_file(seq_ / "thesis.tex"), "precious");
  EXPECT_EQ(names_in(seq_), std::set<std::string>{"thesis.tex"});
  EXPECT_EQ(names_in(dir_), std::set<std::string>{"seq"});
}

TEST_F(SequenceFolder, RefusesAFile) {
  write_text(seq_, "not a folder");
  input_error_of([&] { SequenceWriter w(seq_.string()); });
  EXPECT_EQ(read_file(seq_), "not a folder");
}

TEST_F(SequenceFolder, WritesIntoAnEmptyExistingFolder) {
  fs::create_directories(seq_);
  write_sequence(seq_);
  EXPECT_EQ(SequenceReader(seq_.string()).size(), 3u);
  EXPECT_EQ(names_in(dir_), std::set<std::string>{"seq"});
}

TEST_F(SequenceFolder, CreatesMissingParents) {
  const fs::path deep = dir_ / "a" / "b" / "seq";
  write_sequence(deep);
  EXPECT_EQ(SequenceReader(deep.string()).size(), 3u);
}

TEST_F(SequenceFolder, TrailingSlashNamesTheSameFolder) {
  write_sequence(seq_.string() + "/");
  EXPECT_EQ(names_in(dir_), std::set<std::string>{"seq"});
  EXPECT_EQ(SequenceReader(seq_.string()).size(), 3u);
}

TEST_F(SequenceFolder, OverwritingAnEarlierSequenceReplacesIt) {
  write_sequence(seq_, 3);
  write_text(seq_ / "notes.txt", "from the first run");
  // Second run: 2 scans, no optional files.
  {
    std::mt19937 rng(5);
    SequenceWriter w(seq_.string());
    w.write_scan(0, random_cloud(rng, 4, true, false));
    w.write_scan(1, random_cloud(rng, 6, true, false));
    SequenceInfo info;
    info.times = {7.0, 8.0};
    info.odometry = {Pose3::Identity(), Pose3::Identity()};
    w.commit(info);
  }
  const SequenceReader r(seq_.string());
  EXPECT_EQ(r.size(), 2u);
  EXPECT_DOUBLE_EQ(r.info().times[0], 7.0);
  EXPECT_TRUE(r.info().groundtruth.empty());
  EXPECT_FALSE(r.info().has_rooms);
  EXPECT_EQ(r.scan(1).size(), 6u);
  EXPECT_FALSE(r.scan(0).has_labels());
  // Nothing of the first run is left.
  EXPECT_FALSE(fs::exists(seq_ / "scans/000002.bin"));
  EXPECT_FALSE(fs::exists(seq_ / "scans/000000.label"));
  EXPECT_FALSE(fs::exists(seq_ / "groundtruth.txt"));
  EXPECT_FALSE(fs::exists(seq_ / "scene.yaml"));
  EXPECT_FALSE(fs::exists(seq_ / "notes.txt"));
  EXPECT_EQ(names_in(dir_), std::set<std::string>{"seq"});
}

TEST_F(SequenceFolder, InstanceIdInTheHighBitsReadsAsTheClass) {
  PointCloud c;
  c.points = {Eigen::Vector3f(1, 2, 3), Eigen::Vector3f(4, 5, 6), Eigen::Vector3f(7, 8, 9)};
  c.labels = {(7u << 16) | 4u, 1u, (0xFFFFu << 16) | 6u};
  {
    SequenceWriter w(seq_.string());
    w.write_scan(0, c);
    SequenceInfo info;
    info.times = {1.0};
    info.odometry = {Pose3::Identity()};
    w.commit(info);
  }
  const PointCloud got = SequenceReader(seq_.string()).scan(0);
  EXPECT_EQ(got.labels, (std::vector<std::uint32_t>{4u, 1u, 6u}));
}

// ---------------------------------------------------------------- reader errors

TEST_F(SequenceFolder, ReaderRejectsAMissingFolder) {
  const std::string msg = input_error_of([&] { SequenceReader r((dir_ / "nope").string()); });
  EXPECT_THAT(msg, HasSubstr((dir_ / "nope").string()));
}

TEST_F(SequenceFolder, ReaderRejectsMissingTimes) {
  write_sequence(seq_);
  fs::remove(seq_ / "times.txt");
  const std::string msg = input_error_of([&] { SequenceReader r(seq_.string()); });
  EXPECT_THAT(msg, HasSubstr("times.txt"));
}

TEST_F(SequenceFolder, ReaderRejectsBadTimes) {
  write_sequence(seq_);
  write_text(seq_ / "times.txt", "1000.0\n1000.1\nabc\n");
  EXPECT_THAT(input_error_of([&] { SequenceReader r(seq_.string()); }),
              StartsWith((seq_ / "times.txt").string() + ":3: "));
  write_text(seq_ / "times.txt", "1000.0\n999.0\n1000.2\n");
  EXPECT_THAT(input_error_of([&] { SequenceReader r(seq_.string()); }),
              StartsWith((seq_ / "times.txt").string() + ":2: "));
  write_text(seq_ / "times.txt", "# no scans\n");
  EXPECT_THAT(input_error_of([&] { SequenceReader r(seq_.string()); }), HasSubstr("times.txt"));
}

TEST_F(SequenceFolder, ReaderRejectsMissingOdometry) {
  write_sequence(seq_);
  fs::remove(seq_ / "odom.txt");
  EXPECT_THAT(input_error_of([&] { SequenceReader r(seq_.string()); }), HasSubstr("odom.txt"));
}

TEST_F(SequenceFolder, ReaderRejectsFewerPosesThanTimes) {
  write_sequence(seq_);
  const std::string odom = read_file(seq_ / "odom.txt");
  write_text(seq_ / "odom.txt", odom.substr(0, odom.rfind('\n', odom.size() - 2) + 1));  // drop the last line
  const std::string msg = input_error_of([&] { SequenceReader r(seq_.string()); });
  EXPECT_THAT(msg, StartsWith((seq_ / "odom.txt").string()));
  EXPECT_THAT(msg, HasSubstr("2 poses"));
}

TEST_F(SequenceFolder, ReaderRejectsGroundTruthWithOtherTimestamps) {
  write_sequence(seq_);
  write_text(seq_ / "groundtruth.txt",
             "1000.000000123 0 0 0 0 0 0 1\n1000.100000123 0 0 0 0 0 0 1\n1000.3 0 0 0 0 0 0 1\n");
  const std::string msg = input_error_of([&] { SequenceReader r(seq_.string()); });
  EXPECT_THAT(msg, StartsWith((seq_ / "groundtruth.txt").string() + ":3: "));
}

TEST_F(SequenceFolder, ReaderRejectsAMissingScan) {
  write_sequence(seq_);
  fs::remove(seq_ / "scans/000002.bin");
  EXPECT_THAT(input_error_of([&] { SequenceReader r(seq_.string()); }), HasSubstr("000002.bin"));
}

// Issue 52: a scan file beyond the count of times and poses was left out without a word. The
// files agree in number: the first extra scan, in name order, is named.
TEST_F(SequenceFolder, ReaderRejectsAScanBeyondTheTimesAndPoses) {
  write_sequence(seq_);
  fs::copy_file(seq_ / "scans/000000.bin", seq_ / "scans/000004.bin");
  fs::copy_file(seq_ / "scans/000000.bin", seq_ / "scans/000003.bin");
  EXPECT_EQ(input_error_of([&] { SequenceReader r(seq_.string()); }),
            (seq_ / "scans/000003.bin").string() +
                ": a scan beyond the 3 of times.txt and odom.txt: a sequence folder's files agree in number");
  // Another spelling of a listed scan's number is no listed scan; other files are not scans.
  fs::remove(seq_ / "scans/000003.bin");
  fs::remove(seq_ / "scans/000004.bin");
  write_text(seq_ / "scans/notes.txt", "calibration done\n");
  write_text(seq_ / "scans/000000.bin.orig", "");
  EXPECT_EQ(SequenceReader(seq_.string()).size(), 3u);
  fs::copy_file(seq_ / "scans/000001.bin", seq_ / "scans/0000001.bin");
  EXPECT_THAT(input_error_of([&] { SequenceReader r(seq_.string()); }),
              StartsWith((seq_ / "scans/0000001.bin").string() + ": a scan beyond"));
}

TEST_F(SequenceFolder, ReaderRejectsABinOfOddSize) {
  write_sequence(seq_);
  write_text(seq_ / "scans/000001.bin", std::string(17, '\0'));
  const SequenceReader r(seq_.string());
  EXPECT_EQ(r.scan(0).size(), 50u);
  const std::string msg = input_error_of([&] { r.scan(1); });
  EXPECT_THAT(msg, StartsWith((seq_ / "scans/000001.bin").string()));
}

TEST_F(SequenceFolder, ReaderRejectsALabelFileOfTheWrongCount) {
  write_sequence(seq_);
  write_text(seq_ / "scans/000000.label", std::string(3 * 4, '\0'));
  const SequenceReader r(seq_.string());
  const std::string msg = input_error_of([&] { r.scan(0); });
  EXPECT_THAT(msg, StartsWith((seq_ / "scans/000000.label").string()));
  EXPECT_THAT(msg, HasSubstr("3 labels for 50 points"));
  // Not a whole number of labels either.
  write_text(seq_ / "scans/000001.label", std::string(7 * 4 + 2, '\0'));
  EXPECT_THAT(input_error_of([&] { r.scan(1); }), StartsWith((seq_ / "scans/000001.label").string()));
}

// What a run asks of a scan that is no keyframe (presence): the same as reading it tells, and
// the same errors, without building the cloud. Scans: 50 points, none (empty), 2 all NaN, one
// NaN then a finite point, 3000 NaN points then a finite one (past the first block read), and
// one with per-point times.
TEST_F(SequenceFolder, PresenceTellsWhatTheScanHoldsWithScansErrors) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  PointCloud nans, late, timed;
  nans.points = {Eigen::Vector3f(nan, 0, 0), Eigen::Vector3f(0, nan, 1)};
  late.points = {Eigen::Vector3f(nan, nan, nan), Eigen::Vector3f(1, 2, 3)};
  PointCloud far_late;
  far_late.points.assign(3000, Eigen::Vector3f(0, 0, nan));
  far_late.points.emplace_back(1, 1, 1);
  timed.points = {Eigen::Vector3f(1, 2, 3)};
  timed.times = {0.05f};
  make_clouds();
  const std::vector<PointCloud> scans = {clouds_[0], PointCloud(), nans, late, far_late, timed};
  {
    SequenceWriter w(seq_.string());
    for (std::size_t i = 0; i < scans.size(); ++i) w.write_scan(i, scans[i]);
    w.commit(make_info(scans.size()));
  }
  const SequenceReader r(seq_.string());
  EXPECT_TRUE(r.presence_is_cheap());
  for (std::size_t i = 0; i < scans.size(); ++i) {
    SCOPED_TRACE(i);
    const PointCloud read = r.scan(i);
    const ScanPresence p = r.presence(i);
    const ScanPresence from_scan = r.ScanSequence::presence(i);  // the default: the scan read whole
    EXPECT_EQ(p.empty, read.empty());
    EXPECT_EQ(p.has_times, read.has_times());
    EXPECT_EQ(p.has_finite, i == 0 || i == 3 || i == 4 || i == 5);
    EXPECT_EQ(p.empty, from_scan.empty);
    EXPECT_EQ(p.has_finite, from_scan.has_finite);
    EXPECT_EQ(p.has_times, from_scan.has_times);
  }
  // A .bin of odd size and a label file of the wrong count: scan()'s errors, word for word.
  write_text(seq_ / "scans/000001.bin", std::string(17, '\0'));
  EXPECT_EQ(input_error_of([&] { r.presence(1); }), input_error_of([&] { r.scan(1); }));
  write_text(seq_ / "scans/000000.label", std::string(3 * 4, '\0'));
  EXPECT_EQ(input_error_of([&] { r.presence(0); }), input_error_of([&] { r.scan(0); }));
  EXPECT_THAT(input_error_of([&] { r.presence(0); }), HasSubstr("3 labels for 50 points"));
  fs::remove(seq_ / "scans/000003.bin");
  EXPECT_EQ(input_error_of([&] { r.presence(3); }), input_error_of([&] { r.scan(3); }));
}

TEST_F(SequenceFolder, ReaderRejectsMalformedRooms) {
  write_sequence(seq_);
  const std::string rooms = (seq_ / "rooms_gt.json").string();
  write_text(rooms, "[{\"name\": \"a\", \"level\": \"L0\"");
  EXPECT_THAT(input_error_of([&] { SequenceReader r(seq_.string()); }), StartsWith(rooms));
  write_text(rooms, "{\"name\": \"a\"}");
  EXPECT_THAT(input_error_of([&] { SequenceReader r(seq_.string()); }), StartsWith(rooms));
  write_text(rooms, "[{\"name\": \"a\", \"level\": \"L0\", \"polygon\": [[0, 0], [1, 0]]}]");
  EXPECT_THAT(input_error_of([&] { SequenceReader r(seq_.string()); }), StartsWith(rooms));
  write_text(rooms, "[{\"name\": \"a\", \"level\": \"L0\", \"polygon\": [[0, 0], [1, \"x\"], [1, 1]]}]");
  EXPECT_THAT(input_error_of([&] { SequenceReader r(seq_.string()); }), StartsWith(rooms));
  write_text(rooms, "[{\"level\": \"L0\", \"polygon\": [[0, 0], [1, 0], [1, 1]]}]");
  EXPECT_THAT(input_error_of([&] { SequenceReader r(seq_.string()); }), StartsWith(rooms));
}
