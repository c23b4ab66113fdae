// `tsgraphs generate` as a user calls it: a scene file that the other commands take, the same
// bytes for the same seed, and bad options refused with nothing written.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "test_support.hpp"
#include "tsgraphs/scene/scene_loader.hpp"

namespace fs = std::filesystem;
using namespace tsgraphs;
using ::testing::HasSubstr;

namespace {

class GenerateCli : public test::TempDirTest {};

}  // namespace

TEST_F(GenerateCli, WritesASceneThatDrawsAndSimulates) {
  const fs::path scene = dir_ / "office.yaml", again = dir_ / "again.yaml";
  std::string err;
  ASSERT_EQ(test::cli("generate --style office --seed 4 --size 0.3 --laps 1 --out " + scene.string(), &err),
            0)
      << err;
  EXPECT_THAT(err, HasSubstr("generate: office, seed 4"));
  ASSERT_EQ(
      test::cli("-q generate --style office --seed 4 --size 0.3 --laps 1 --out " + again.string(), &err), 0)
      << err;
  EXPECT_EQ(test::read_file(scene), test::read_file(again));
  EXPECT_TRUE(scene::load_scene(scene.string()).warnings.empty());
  ASSERT_EQ(test::cli("-q draw-scene " + scene.string() + " --out " + (dir_ / "office.svg").string(), &err),
            0)
      << err;
  EXPECT_TRUE(err.empty()) << err;  // no warning about the path or the scene
  ASSERT_EQ(test::cli("-q simulate " + scene.string() + " --out " + (dir_ / "seq").string(), &err), 0) << err;
  EXPECT_TRUE(err.empty()) << err;
  EXPECT_TRUE(fs::exists(dir_ / "seq" / "rooms_gt.json"));
}

TEST_F(GenerateCli, BoundsAreCheckedBeforeAnyWorkInOneLine) {
  const fs::path out = dir_ / "x.yaml";
  std::string err;
  // CLI11's own checks printed DBL_MAX in 309 digits on two lines.
  EXPECT_EQ(test::cli("generate --style office --laps 0 --out " + out.string(), &err), 2);
  EXPECT_EQ(err, "tsgraphs: error: --laps: must be a whole number in [1, 10000], not '0'\n");
  EXPECT_EQ(test::cli("generate --style office --laps 1e9 --out " + out.string(), &err), 2);
  EXPECT_EQ(err, "tsgraphs: error: --laps: must be a whole number in [1, 10000], not '1e9'\n");
  // 10,000 laps are within the bound of laps but not of scans: refused before the path is built
  // (it ran for minutes).
  EXPECT_EQ(test::cli("generate --style office --laps 10000 --out " + out.string(), &err), 2);
  EXPECT_NE(err.find("tsgraphs: error: --laps: the path makes"), std::string::npos) << err;
  EXPECT_NE(err.find("more than 1000000"), std::string::npos) << err;
  // A seed beyond 2^63-1 was clamped to it: every such seed gave the same building.
  EXPECT_EQ(test::cli("generate --style office --seed 9223372036854775808 --out " + out.string(), &err), 2);
  EXPECT_EQ(err,
            "tsgraphs: error: --seed: must be a whole number in [0, 9223372036854775807], not "
            "'9223372036854775808'\n");
  EXPECT_EQ(test::cli("generate --style office --out " + out.string() + " --no-such-option", &err), 2);
  EXPECT_EQ(err.rfind("tsgraphs: error: ", 0), 0u) << err;
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
  EXPECT_EQ(test::cli("--threads 100000 generate --style office --out " + out.string(), &err), 2);
  EXPECT_NE(err.find("--threads: must be a whole number in [0, 1024]"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(out));
  EXPECT_EQ(test::cli("--help", &err), 0);
}

TEST_F(GenerateCli, BadOptionsAreRefusedAndNothingIsWritten) {
  const fs::path out = dir_ / "x.yaml";
  std::string err;
  EXPECT_EQ(test::cli("generate --style castle --seed 1 --out " + out.string(), &err), 2);
  EXPECT_THAT(err, HasSubstr("unknown building style 'castle'"));
  EXPECT_THAT(err, HasSubstr("office, atrium"));
  EXPECT_EQ(test::cli("generate --style office --seed 1 --size 0 --out " + out.string(), &err), 2);
  EXPECT_THAT(err, HasSubstr("--size"));
  EXPECT_EQ(test::cli("generate --style office --seed -3 --out " + out.string(), &err), 2);
  EXPECT_EQ(
      test::cli("generate --style office --seed 1 --out " + (dir_ / "no" / "such" / "x.yaml").string(), &err),
      2);
  EXPECT_FALSE(fs::exists(out));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 0);
}
