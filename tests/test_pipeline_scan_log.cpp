// The scan log: every scan's record back in order, whether it stayed in memory or spilled to
// the temporary file, and appends after reading back.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "tsgraphs/pipeline/scan_log.hpp"

using namespace tsgraphs;
using namespace tsgraphs::pipeline;

namespace {

ScanRecord record_of(std::size_t i) {
  ScanRecord r;
  r.scan_index = i;
  r.stamp = 0.1 * static_cast<double>(i) + 1e9;  // a UNIX time: every bit of the double matters
  r.keyframe = i % 7 == 0 ? static_cast<int>(i / 7) : -1;
  r.reference_keyframe = static_cast<int>(i / 7);
  r.odom =
      make_pose(Eigen::Vector3d(0.01 * static_cast<double>(i), -2.0, 0.5), 0.001 * static_cast<double>(i));
  r.num_points = 1000 + i;
  r.prefilter_ms = 1.5;
  r.ground_ms = 2.25;
  r.num_ground_nodes = i % 13;
  r.rooms_ms = 0.125;
  r.ground_tp = static_cast<long>(i);
  r.ground_fp = -1;
  r.ground_fn = 3;
  r.walls_ms = 4.0;
  r.loop_ms = 0.5;
  r.frontend_ms = 9.75;
  if (i % 5 == 0) r.warning = "empty scan: skipped " + std::to_string(i);
  return r;
}

void expect_same(const ScanRecord& a, const ScanRecord& b) {
  EXPECT_EQ(a.scan_index, b.scan_index);
  EXPECT_EQ(a.stamp, b.stamp);
  EXPECT_EQ(a.keyframe, b.keyframe);
  EXPECT_EQ(a.reference_keyframe, b.reference_keyframe);
  EXPECT_EQ(a.odom.matrix(), b.odom.matrix());
  EXPECT_EQ(a.num_points, b.num_points);
  EXPECT_EQ(a.prefilter_ms, b.prefilter_ms);
  EXPECT_EQ(a.ground_ms, b.ground_ms);
  EXPECT_EQ(a.num_ground_nodes, b.num_ground_nodes);
  EXPECT_EQ(a.rooms_ms, b.rooms_ms);
  EXPECT_EQ(a.ground_tp, b.ground_tp);
  EXPECT_EQ(a.ground_fp, b.ground_fp);
  EXPECT_EQ(a.ground_fn, b.ground_fn);
  EXPECT_EQ(a.walls_ms, b.walls_ms);
  EXPECT_EQ(a.loop_ms, b.loop_ms);
  EXPECT_EQ(a.frontend_ms, b.frontend_ms);
  EXPECT_EQ(a.warning, b.warning);
}

std::vector<ScanRecord> read_all(const ScanLog& log) {
  std::vector<ScanRecord> out;
  log.for_each([&](const ScanRecord& r) { out.push_back(r); });
  return out;
}

}  // namespace

TEST(ScanLog, RecordsComeBackInOrderAcrossSpills) {
  ScanLog log(16);  // a small memory share: most records spill
  EXPECT_TRUE(log.empty());
  EXPECT_TRUE(read_all(log).empty());
  for (std::size_t i = 0; i < 100; ++i) log.append(record_of(i));
  EXPECT_EQ(log.size(), 100u);
  std::vector<ScanRecord> back = read_all(log);
  ASSERT_EQ(back.size(), 100u);
  for (std::size_t i = 0; i < back.size(); ++i) expect_same(back[i], record_of(i));

  // Appending after a read-back continues the sequence; a second read gives all again.
  for (std::size_t i = 100; i < 250; ++i) log.append(record_of(i));
  back = read_all(log);
  ASSERT_EQ(back.size(), 250u);
  for (std::size_t i = 0; i < back.size(); ++i) expect_same(back[i], record_of(i));
}

TEST(ScanLog, AMovedLogKeepsItsRecords) {
  ScanLog log(4);
  for (std::size_t i = 0; i < 10; ++i) log.append(record_of(i));
  ScanLog moved = std::move(log);
  EXPECT_EQ(moved.size(), 10u);
  const std::vector<ScanRecord> back = read_all(moved);
  ASSERT_EQ(back.size(), 10u);
  for (std::size_t i = 0; i < back.size(); ++i) expect_same(back[i], record_of(i));
}
