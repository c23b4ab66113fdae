#pragma once
/// What every fuzz target shares: readers that take a path get the input as a file, and bad
/// input may only be answered with an InputError (the front end's exit 2). Any other exception
/// would reach the user as exit 1 "internal error": a finding, so the target aborts on it.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>

#include "tsgraphs/core/error.hpp"

namespace tsgraphs::fuzz {

/// A folder of this process's own, removed at exit.
inline const std::filesystem::path& scratch_dir() {
  struct Scratch {
    std::filesystem::path dir;
    Scratch()
        : dir(std::filesystem::temp_directory_path() / ("tsgraphs-fuzz-" + std::to_string(::getpid()))) {
      std::filesystem::create_directories(dir);
    }
    ~Scratch() {
      std::error_code ec;
      std::filesystem::remove_all(dir, ec);
    }
  };
  static const Scratch scratch;
  return scratch.dir;
}

/// The input as the file `name` in the scratch folder (rewritten for every input), for readers
/// that take a path.
inline std::string input_file(const std::uint8_t* data, std::size_t size, const std::string& name) {
  const std::string path = (scratch_dir() / name).string();
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  out.close();
  if (!out) {
    std::fprintf(stderr, "fuzz: cannot write %s\n", path.c_str());
    std::abort();
  }
  return path;
}

/// What the readers of the current input answered: the replay driver checks that every seed
/// is read by at least one of its target's readers (a seed every reader refuses tests nothing).
struct Tally {
  std::size_t reads = 0, refusals = 0;
  std::string refusal;  ///< the last refusal's message
};
inline Tally& tally() {
  static Tally t;
  return t;
}

/// Runs `read`; an InputError is a correct answer to bad input, anything else aborts.
template <class Read>
void only_input_errors(const char* reader, Read&& read) {
  ++tally().reads;
  try {
    read();
  } catch (const InputError& e) {
    ++tally().refusals;
    tally().refusal = e.what();
    // To see what the readers answer: TSGRAPHS_FUZZ_PRINT_REFUSALS=1 fuzz_<target> ...
    static const bool print = std::getenv("TSGRAPHS_FUZZ_PRINT_REFUSALS") != nullptr;
    if (print) std::fprintf(stderr, "refused: %s\n", e.what());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fuzz: %s threw something other than an InputError: %s\n", reader, e.what());
    std::abort();
  } catch (...) {
    std::fprintf(stderr, "fuzz: %s threw something other than an exception\n", reader);
    std::abort();
  }
}

}  // namespace tsgraphs::fuzz
