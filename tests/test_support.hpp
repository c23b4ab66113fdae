#pragma once
/// Scaffolding shared by the test executables: a fresh temporary folder per test, and the message
/// of the InputError a piece of code throws. Header only: tests/CMakeLists.txt makes an executable
/// of every tests/test_*.cpp, so this file must not become one.
#include <gtest/gtest.h>
#include <unistd.h>

#include <exception>
#include <filesystem>
#include <fstream>
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
