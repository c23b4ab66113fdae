/// The fuzz targets without libFuzzer (gcc builds, ctest): each seed of a corpus folder, then a
/// fixed number of deterministic mutations of it (bit flips, boundary values in length words,
/// cuts, insertions, copies, numbers swapped for extreme ones). The same arguments give the
/// same inputs; on a crash the input being run is printed.
/// Every seed must be read by at least one of the target's readers without an error, but for
/// regression_* seeds (inputs that once crashed a reader, kept so that they stay fixed).
/// Usage: fuzz_<target> CORPUS_DIR [MUTATIONS_PER_SEED=100] [SEED=1]
#include <algorithm>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include <unistd.h>

#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

char current[512] = "no input yet";

void report_crash(int signal) {
  const char prefix[] = "fuzz replay: crashed on ";
  (void)!::write(2, prefix, sizeof prefix - 1);
  (void)!::write(2, current, std::strlen(current));
  (void)!::write(2, "\n", 1);
  std::signal(signal, SIG_DFL);
  std::raise(signal);
}

using Rng = std::mt19937_64;

std::size_t below(Rng& rng, std::size_t n) { return n == 0 ? 0 : static_cast<std::size_t>(rng() % n); }

/// A number token (digits with sign, point, exponent) at or after `from`, as [begin, end).
bool find_number(const std::string& s, std::size_t from, std::size_t& begin, std::size_t& end) {
  begin = s.find_first_of("0123456789", from);
  if (begin == std::string::npos) return false;
  if (begin > 0 && (s[begin - 1] == '-' || s[begin - 1] == '.')) --begin;
  end = begin + 1;
  while (end < s.size() && std::strchr("0123456789.eE+-", s[end]) != nullptr) ++end;
  return true;
}

void mutate_once(std::string& s, Rng& rng) {
  static const std::uint32_t kWords[] = {0u,          1u,          0x7fu,       0xffu,
                                         0x7fffffffu, 0x80000000u, 0xfffffffeu, 0xffffffffu};
  static const char* const kNumbers[] = {"0",
                                         "-1",
                                         "1e308",
                                         "-1e308",
                                         "1e400",
                                         "nan",
                                         "inf",
                                         "1e-9",
                                         "4294967296",
                                         "2147483648",
                                         "99999999999999999999",
                                         "0.5"};
  switch (below(rng, 8)) {
    case 0:  // one bit
      if (!s.empty()) s[below(rng, s.size())] ^= static_cast<char>(1u << below(rng, 8));
      break;
    case 1: {  // a boundary byte
      static const unsigned char kBytes[] = {0x00, 0x01, 0x7f, 0x80, 0xff, '\n', ' ', ':'};
      if (!s.empty()) s[below(rng, s.size())] = static_cast<char>(kBytes[below(rng, sizeof kBytes)]);
      break;
    }
    case 2: {  // a boundary length word (little-endian, as bags and PCD size words are)
      if (s.size() < 4) break;
      const std::uint32_t word = kWords[below(rng, std::size(kWords))];
      std::memcpy(&s[below(rng, s.size() - 3)], &word, 4);
      break;
    }
    case 3:  // cut short
      s.resize(below(rng, s.size() + 1));
      break;
    case 4: {  // a range removed
      const std::size_t at = below(rng, s.size() + 1);
      s.erase(at, 1 + below(rng, 16));
      break;
    }
    case 5: {  // random bytes inserted
      std::string bytes(1 + below(rng, 16), '\0');
      for (char& c : bytes) c = static_cast<char>(rng());
      s.insert(below(rng, s.size() + 1), bytes);
      break;
    }
    case 6: {  // a range copied elsewhere
      if (s.empty()) break;
      const std::size_t from = below(rng, s.size());
      const std::string piece = s.substr(from, 1 + below(rng, 64));
      s.insert(below(rng, s.size() + 1), piece);
      break;
    }
    default: {  // a number made extreme
      std::size_t begin, end;
      if (find_number(s, below(rng, s.size() + 1), begin, end) || find_number(s, 0, begin, end)) {
        s.replace(begin, end - begin, kNumbers[below(rng, std::size(kNumbers))]);
      }
      break;
    }
  }
}

void run(const std::string& input) {
  LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(input.data()), input.size());
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || argc > 4) {
    std::fprintf(stderr, "usage: %s CORPUS_DIR [MUTATIONS_PER_SEED=100] [SEED=1]\n", argv[0]);
    return 2;
  }
  const std::filesystem::path dir = argv[1];
  const long mutations = argc > 2 ? std::stol(argv[2]) : 100;
  const unsigned long seed = argc > 3 ? std::stoul(argv[3]) : 1;
  std::vector<std::filesystem::path> seeds;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
    if (entry.is_regular_file()) seeds.push_back(entry.path());
  }
  if (ec || seeds.empty()) {
    std::fprintf(stderr, "%s: no seed files\n", dir.c_str());
    return 2;
  }
  std::sort(seeds.begin(), seeds.end());
  std::signal(SIGSEGV, report_crash);
  std::signal(SIGABRT, report_crash);
  std::signal(SIGFPE, report_crash);
  std::signal(SIGBUS, report_crash);
  std::size_t runs = 0;
  for (const auto& path : seeds) {
    std::ifstream in(path, std::ios::binary);
    const std::string original((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::snprintf(current, sizeof current, "%s (unmutated)", path.filename().c_str());
    tsgraphs::fuzz::tally() = {};
    run(original);
    ++runs;
    const tsgraphs::fuzz::Tally& seed_tally = tsgraphs::fuzz::tally();
    // regression_* seeds are inputs that once crashed a reader: refusing them is right.
    const bool regression = path.filename().string().rfind("regression_", 0) == 0;
    if (!regression && seed_tally.refusals == seed_tally.reads) {
      std::fprintf(stderr, "%s: every reader refuses this seed: %s\n", path.c_str(),
                   seed_tally.refusal.c_str());
      return 1;
    }
    Rng rng(seed ^ std::hash<std::string>{}(path.filename().string()));
    for (long m = 0; m < mutations; ++m) {
      std::snprintf(current, sizeof current, "%s, mutation %ld (seed %lu)", path.filename().c_str(), m, seed);
      std::string input = original;
      const std::size_t stacked = 1 + below(rng, 4);
      for (std::size_t k = 0; k < stacked; ++k) mutate_once(input, rng);
      run(input);
      ++runs;
    }
  }
  std::printf("%zu inputs from %zu seeds, no crash\n", runs, seeds.size());
  return 0;
}
