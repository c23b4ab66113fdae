/// Fuzz target: the building generator (`generate`, a suite's generate cases) on options from
/// bytes: style, seed, size, laps, people, realistic. Laps, people and seeds are taken as the
/// bytes spell them, beyond their bounds too (which must be InputErrors); the size is kept small
/// (at most kMaxSize) so that each input is generated in well under a second. An input of fewer
/// bytes than kInputBytes is padded with zeros.
#include <algorithm>
#include <cstring>

#include "fuzz_support.hpp"
#include "tsgraphs/generator/generator.hpp"

namespace {

/// The input's layout: a style index (one past the last style is an unknown style), the seed
/// (8 bytes), the size (1 byte: 1..256 parts of kMaxSize), laps (4 bytes, signed), people (1
/// byte, signed) and realistic (its lowest bit), little-endian.
constexpr std::size_t kStyleAt = 0, kSeedAt = 1, kSizeAt = 9, kLapsAt = 10, kPeopleAt = 14, kRealisticAt = 15;
constexpr std::size_t kInputBytes = 16;
constexpr double kMaxSize = 0.3;
constexpr int kSizeSteps = 256;

template <class T>
T field(const std::uint8_t* input, std::size_t at) {
  T value;
  std::memcpy(&value, input + at, sizeof value);
  return value;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace tsgraphs;
  std::uint8_t input[kInputBytes] = {};
  std::memcpy(input, data, std::min(size, kInputBytes));
  const std::vector<std::string>& styles = generator::building_style_names();
  const std::size_t style_index = input[kStyleAt] % (styles.size() + 1);
  const std::string style = style_index < styles.size() ? styles[style_index] : "no_such_style";
  generator::GeneratorConfig config;
  config.size = kMaxSize * (input[kSizeAt] + 1) / kSizeSteps;
  config.laps = field<std::int32_t>(input, kLapsAt);
  config.people = field<std::int8_t>(input, kPeopleAt);
  config.realistic = (input[kRealisticAt] & 1) != 0;
  const auto seed = field<std::uint64_t>(input, kSeedAt);
  fuzz::only_input_errors("generate_building", [&] { generator::generate_building(style, seed, config); });
  return 0;
}
