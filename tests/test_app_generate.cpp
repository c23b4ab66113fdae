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
  ASSERT_EQ(test::cli("generate --style office --seed 4 --size 0.3 --laps 1 --out " + scene.string(), &err), 0) << err;
  EXPECT_THAT(err, HasSubstr("generate: office, seed 4"));
  ASSERT_EQ(test::cli("-q generate --style office --seed 4 --size 0.3 --laps 1 --out " + again.string(), &err), 0) << err;
  EXPECT_EQ(test::read_file(scene), test::read_file(again));
  EXPECT_TRUE(scene::load_scene(scene.string()).warnings.empty());
  ASSERT_EQ(test::cli("-q draw-scene " + scene.string() + " --out " + (dir_ / "office.svg").string(), &err), 0) << err;
  EXPECT_TRUE(err.empty()) << err;  // no warning about the path or the scene
  ASSERT_EQ(test::cli("-q simulate " + scene.string() + " --out " + (dir_ / "seq").string(), &err), 0) << err;
  EXPECT_TRUE(err.empty()) << err;
  EXPECT_TRUE(fs::exists(dir_ / "seq" / "rooms_gt.json"));
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
  EXPECT_EQ(test::cli("generate --style office --seed 1 --out " + (dir_ / "no" / "such" / "x.yaml").string(), &err), 2);
  EXPECT_FALSE(fs::exists(out));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 0);
}
