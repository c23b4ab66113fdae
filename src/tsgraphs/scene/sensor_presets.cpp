#include "tsgraphs/scene/sensor_presets.hpp"

namespace tsgraphs::scene {
namespace {

struct Preset {
  const char* name;
  int channels;
  int columns;  // at 10 Hz
  double fov_min_deg;
  double fov_max_deg;
  double beam_step_deg;  // > 0: the datasheet's fixed spacing from fov_max down
  double max_range;
  double min_range;
  double range_noise_std;
};

// Datasheet values. Ouster OS1-64 and OS0-128 (rev 6/7, "uniform" beam configuration),
// Velodyne VLP-16 (2.0 deg steps, 1800 firings at 10 Hz = 0.2 deg), Hesai XT32 (1.0 deg steps
// from +15 to -16, 2000 firings at 10 Hz = 0.18 deg). Noise: the makers' 1-sigma precision
// at indoor ranges.
constexpr Preset kPresets[] = {
    {"os1-64", 64, 1024, -22.5, 22.5, 0.0, 120.0, 0.3, 0.015},
    {"os0-128", 128, 1024, -45.0, 45.0, 0.0, 50.0, 0.3, 0.015},
    {"vlp-16", 16, 1800, -15.0, 15.0, 2.0, 100.0, 0.5, 0.015},
    {"hesai-xt32", 32, 2000, -16.0, 15.0, 1.0, 120.0, 0.05, 0.01},
};

}  // namespace

const std::vector<std::string>& preset_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const Preset& p : kPresets) n.emplace_back(p.name);
    return n;
  }();
  return names;
}

std::vector<double> evenly_spaced_angles(int channels, double min_deg, double max_deg) {
  std::vector<double> angles(static_cast<std::size_t>(std::max(channels, 0)));
  for (int i = 0; i < channels; ++i) {
    angles[i] =
        channels == 1 ? 0.5 * (min_deg + max_deg) : max_deg - (max_deg - min_deg) * i / (channels - 1.0);
  }
  return angles;
}

bool apply_preset(const std::string& name, SensorSpec* spec) {
  for (const Preset& p : kPresets) {
    if (name != p.name) continue;
    spec->preset = p.name;
    spec->channels = p.channels;
    spec->columns = p.columns;
    spec->vertical_fov_min_deg = p.fov_min_deg;
    spec->vertical_fov_max_deg = p.fov_max_deg;
    spec->vertical_angles_deg = evenly_spaced_angles(p.channels, p.fov_min_deg, p.fov_max_deg);
    if (p.beam_step_deg > 0.0) {  // the datasheet's fixed step, exact rather than interpolated
      for (int i = 0; i < p.channels; ++i) spec->vertical_angles_deg[i] = p.fov_max_deg - i * p.beam_step_deg;
    }
    spec->max_range = p.max_range;
    spec->min_range = p.min_range;
    spec->rate_hz = 10.0;
    spec->range_noise_std = p.range_noise_std;
    return true;
  }
  return false;
}

}  // namespace tsgraphs::scene
