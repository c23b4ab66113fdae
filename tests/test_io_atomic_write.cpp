// Atomic outputs: files written through a temporary sibling and a rename, and folders built
// under a temporary name and moved into place on commit.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/io/atomic_write.hpp"

#include "test_support.hpp"

using namespace tsgraphs;
using namespace tsgraphs::io;
using ::testing::HasSubstr;
using tsgraphs::test::TempDirTest;

namespace fs = std::filesystem;

namespace {

using test::read_file;

std::set<std::string> names_in(const fs::path& dir) {
  std::set<std::string> out;
  for (const auto& e : fs::directory_iterator(dir)) out.insert(e.path().filename().string());
  return out;
}

using AtomicWrite = TempDirTest;
using AtomicDir = AtomicWrite;

}  // namespace

// ---------------------------------------------------------------- write_file_atomic

TEST_F(AtomicWrite, CreatesTheFileWithTheContent) {
  const fs::path p = dir_ / "report.json";
  const std::string content = std::string("{\"a\": 1}\n") + std::string(1, '\0') + "binary\xff tail";
  write_file_atomic(p.string(), content);
  EXPECT_EQ(read_file(p), content);
  EXPECT_EQ(names_in(dir_), std::set<std::string>{"report.json"});
}

TEST_F(AtomicWrite, EmptyContentGivesAnEmptyFile) {
  const fs::path p = dir_ / "empty.txt";
  write_file_atomic(p.string(), "");
  ASSERT_TRUE(fs::is_regular_file(p));
  EXPECT_EQ(fs::file_size(p), 0u);
}

TEST_F(AtomicWrite, LargeContent) {
  std::string content(3 << 20, 'x');
  for (std::size_t i = 0; i < content.size(); i += 4097) content[i] = static_cast<char>('a' + i % 26);
  const fs::path p = dir_ / "big.bin";
  write_file_atomic(p.string(), content);
  EXPECT_EQ(read_file(p), content);
}

TEST_F(AtomicWrite, ReplacesAnExistingFile) {
  const fs::path p = dir_ / "metrics.txt";
  std::ofstream(p) << "an old and much longer content that must be gone entirely\n";
  write_file_atomic(p.string(), "new\n");
  EXPECT_EQ(read_file(p), "new\n");
  write_file_atomic(p.string(), "newer\n");
  EXPECT_EQ(read_file(p), "newer\n");
  EXPECT_EQ(names_in(dir_), std::set<std::string>{"metrics.txt"});
}

TEST_F(AtomicWrite, ManyWritesLeaveNoTemporaryFiles) {
  for (int i = 0; i < 20; ++i) {
    write_file_atomic((dir_ / ("f" + std::to_string(i % 3))).string(), std::to_string(i));
  }
  EXPECT_EQ(names_in(dir_), (std::set<std::string>{"f0", "f1", "f2"}));
  EXPECT_EQ(read_file(dir_ / "f0"), "18");
  EXPECT_EQ(read_file(dir_ / "f1"), "19");
  EXPECT_EQ(read_file(dir_ / "f2"), "17");
}

TEST_F(AtomicWrite, MissingFolderThrowsNamingThePath) {
  const fs::path p = dir_ / "missing" / "out.txt";
  try {
    write_file_atomic(p.string(), "x");
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), HasSubstr(p.string()));
  }
  EXPECT_FALSE(fs::exists(dir_ / "missing"));
  EXPECT_TRUE(names_in(dir_).empty());
}

TEST_F(AtomicWrite, TargetThatIsAFolderThrowsAndLeavesNoTemporaryFile) {
  fs::create_directories(dir_ / "taken");
  std::ofstream(dir_ / "taken" / "inside.txt") << "keep";
  EXPECT_THROW(write_file_atomic((dir_ / "taken").string(), "x"), InputError);  // bad input: exit 2
  EXPECT_EQ(names_in(dir_), std::set<std::string>{"taken"});
  EXPECT_EQ(read_file(dir_ / "taken" / "inside.txt"), "keep");
}

// ---------------------------------------------------------------- AtomicDirectory

TEST_F(AtomicDir, BuildsUnderATemporaryNameAndCommits) {
  const fs::path final_path = dir_ / "out";
  {
    AtomicDirectory d(final_path.string(), "done.txt");
    EXPECT_EQ(d.final_path(), final_path.string());
    EXPECT_NE(d.path(), d.final_path());
    EXPECT_EQ(fs::path(d.path()).parent_path(), dir_);  // a sibling: the rename stays on one file system
    EXPECT_TRUE(fs::is_directory(d.path()));
    EXPECT_FALSE(fs::exists(final_path));
    std::ofstream(fs::path(d.path()) / "done.txt") << "ok";
    d.commit();
    EXPECT_TRUE(fs::is_directory(final_path));
  }
  EXPECT_EQ(read_file(final_path / "done.txt"), "ok");
  EXPECT_EQ(names_in(dir_), std::set<std::string>{"out"});
}

TEST_F(AtomicDir, UncommittedIsRemoved) {
  {
    AtomicDirectory d((dir_ / "out").string(), "done.txt");
    std::ofstream(fs::path(d.path()) / "partial.txt") << "half";
    fs::create_directories(fs::path(d.path()) / "sub" / "deeper");
  }
  EXPECT_TRUE(names_in(dir_).empty());
}

// Issue 18: an error met while the run wrote and read back its outputs named the temporary
// folder, which the user never sees (and which is removed).
TEST_F(AtomicDir, ErrorsNameTheFinalFolder) {
  const std::string out = (dir_ / "out").string();
  AtomicDirectory d(out, "done.txt");
  const InputError e = d.named_as_final(
      InputError(d.path() + "/scene_graph.json: keyframes[3]: not finite (" + d.path() + ")"));
  EXPECT_EQ(std::string(e.what()), out + "/scene_graph.json: keyframes[3]: not finite (" + out + ")");
  EXPECT_EQ(std::string(d.named_as_final(InputError("other.txt:2: bad")).what()), "other.txt:2: bad");
}

TEST_F(AtomicDir, ReplacesAnEarlierOutput) {
  const fs::path final_path = dir_ / "out";
  fs::create_directories(final_path / "old_sub");
  std::ofstream(final_path / "done.txt") << "first";
  std::ofstream(final_path / "stale.txt") << "stale";
  {
    AtomicDirectory d(final_path.string(), "done.txt");
    std::ofstream(fs::path(d.path()) / "done.txt") << "second";
    d.commit();
  }
  EXPECT_EQ(names_in(final_path), std::set<std::string>{"done.txt"});
  EXPECT_EQ(read_file(final_path / "done.txt"), "second");
  EXPECT_EQ(names_in(dir_), std::set<std::string>{"out"});
}

TEST_F(AtomicDir, RefusesAnUnrelatedFolder) {
  const fs::path final_path = dir_ / "home";
  fs::create_directories(final_path);
  std::ofstream(final_path / "thesis.tex") << "precious";
  try {
    AtomicDirectory d(final_path.string(), "done.txt");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr(final_path.string()));
    EXPECT_THAT(e.what(), HasSubstr("done.txt"));
  }
  EXPECT_EQ(names_in(final_path), std::set<std::string>{"thesis.tex"});
  EXPECT_EQ(read_file(final_path / "thesis.tex"), "precious");
  EXPECT_EQ(names_in(dir_), std::set<std::string>{"home"});
}

TEST_F(AtomicDir, RefusesAFile) {
  const fs::path final_path = dir_ / "file";
  std::ofstream(final_path) << "data";
  EXPECT_THROW(AtomicDirectory(final_path.string(), "done.txt"), InputError);
  EXPECT_EQ(read_file(final_path), "data");
  EXPECT_EQ(names_in(dir_), std::set<std::string>{"file"});
}

TEST_F(AtomicDir, RefusesTheRootAndNoName) {
  // `run --out /` ran the whole sequence, then failed to rename its output onto "" (exit 1).
  for (const std::string bad : {"/", "//", "/..", ""}) {
    try {
      AtomicDirectory d(bad, "done.txt");
      FAIL() << "'" << bad << "' accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("not a folder to write into"), std::string::npos) << e.what();
    }
  }
}

TEST_F(AtomicDir, AcceptsAnEmptyFolder) {
  const fs::path final_path = dir_ / "empty";
  fs::create_directories(final_path);
  {
    AtomicDirectory d(final_path.string(), "done.txt");
    std::ofstream(fs::path(d.path()) / "a.txt") << "a";
    d.commit();
  }
  EXPECT_EQ(names_in(final_path), std::set<std::string>{"a.txt"});
  EXPECT_EQ(names_in(dir_), std::set<std::string>{"empty"});
}

TEST_F(AtomicDir, TwoAtOnceDoNotCollide) {
  AtomicDirectory a((dir_ / "x").string(), "m");
  AtomicDirectory b((dir_ / "x").string(), "m");
  EXPECT_NE(a.path(), b.path());
  std::ofstream(fs::path(a.path()) / "m") << "a";
  std::ofstream(fs::path(b.path()) / "m") << "b";
  a.commit();
  b.commit();  // replaces a's output, which carries the marker
  EXPECT_EQ(read_file(dir_ / "x" / "m"), "b");
  EXPECT_EQ(names_in(dir_), std::set<std::string>{"x"});
}
