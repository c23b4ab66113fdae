#pragma once
/// Scaffolding shared by the test executables: a fresh temporary folder per test, a file's bytes,
/// and the message of the InputError a piece of code throws. Header only: tests/CMakeLists.txt makes an
/// executable of every tests/test_*.cpp, so this file must not become one.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <system_error>

#include "tsgraphs/core/error.hpp"

namespace tsgraphs::test {

/// A new, empty folder under ::testing::TempDir(), named after the running test, `tag` (when not
/// empty) and this process, so that tests and parallel runs never share one. Whatever was left there
/// by an earlier run is removed first. The caller removes it.
inline std::filesystem::path fresh_temp_dir(const std::string& tag = "") {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string name = "tsgraphs_";
  if (info != nullptr) name += std::string(info->test_suite_name()) + "_" + info->name() + "_";
  if (!tag.empty()) name += tag + "_";
  name += std::to_string(::getpid());
  for (char& c : name) {
    if (c == '/') c = '_';  // parameterised tests: "Prefix/Suite", "Test/0"
  }
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

/// A fixture that gives each test a fresh temporary folder, `dir_`, made in SetUp and removed with
/// all it holds in TearDown. A fixture that needs more set-up calls TempDirTest::SetUp() first.
class TempDirTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = fresh_temp_dir(); }
  void TearDown() override {
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }

  /// Writes `text` byte for byte to the file `name` in dir_ (replacing it) and returns its path.
  std::string write_file(const std::string& name, const std::string& text) const {
    const std::filesystem::path p = dir_ / name;
    std::ofstream out(p, std::ios::binary);
    out << text;
    out.close();
    if (!out) ADD_FAILURE() << "could not write " << p;
    return p.string();
  }

  std::filesystem::path dir_;
};

/// The bytes of the file at `p` ("" when it cannot be read).
inline std::string read_file(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

#ifdef TSGRAPHS_BINARY
/// Runs the tsgraphs program with `args` (shell words); its stdout into `out` and its stderr into
/// `err` when not null. Returns the exit status (-1 when it did not exit).
inline int run_tsgraphs(const std::string& args, std::string* out, std::string* err) {
  const std::filesystem::path base =
      std::filesystem::path(::testing::TempDir()) / ("tsgraphs_cli_" + std::to_string(::getpid()));
  const std::string o = base.string() + ".out", e = base.string() + ".err";
  const int status =
      std::system((std::string(TSGRAPHS_BINARY) + " " + args + " > " + o + " 2> " + e).c_str());
  if (out != nullptr) *out = read_file(o);
  if (err != nullptr) *err = read_file(e);
  std::filesystem::remove(o);
  std::filesystem::remove(e);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}
/// run_tsgraphs with its stdout dropped.
inline int cli(const std::string& args, std::string* err) { return run_tsgraphs(args, nullptr, err); }
#endif

/// The message of the tsgraphs::InputError that calling `f` throws; a test failure (and "") when it
/// throws nothing or another exception.
template <class F>
std::string input_error_of(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not an InputError: " << e.what();
    return "";
  }
  ADD_FAILURE() << "no error thrown";
  return "";
}

}  // namespace tsgraphs::test
