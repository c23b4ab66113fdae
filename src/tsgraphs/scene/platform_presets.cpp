#include "tsgraphs/scene/platform_presets.hpp"

namespace tsgraphs::scene {

PlatformSpec platform_defaults(PlatformType type) {
  PlatformSpec p;
  p.type = type;
  switch (type) {
    case PlatformType::kWheeled:
      break;
    case PlatformType::kHandheld:
      // A person walking with the sensor held up: a bob at each step (about 1.8 steps per
      // second), roll from side to side over a stride, pitch with each step, the heading
      // wandering by a few degrees about the direction of travel.
      p.bob = 0.03;
      p.step_hz = 1.8;
      p.sway_deg = 4.0;
      p.yaw_jitter_deg = 3.0;
      p.motion_distortion = true;
      break;
    case PlatformType::kLegged:
      // A quadruped trotting: small, faster steps and the impacts' vibration.
      p.bob = 0.01;
      p.step_hz = 2.5;
      p.sway_deg = 1.5;
      p.yaw_jitter_deg = 1.0;
      p.vibration = 0.004;
      p.vibration_hz = 12.0;
      p.motion_distortion = true;
      break;
  }
  return p;
}

const char* platform_name(PlatformType type) {
  switch (type) {
    case PlatformType::kHandheld:
      return "handheld";
    case PlatformType::kLegged:
      return "legged";
    case PlatformType::kWheeled:
      break;
  }
  return "wheeled";
}

std::optional<PlatformType> platform_type(const std::string& name) {
  for (PlatformType t : {PlatformType::kWheeled, PlatformType::kHandheld, PlatformType::kLegged})
    if (name == platform_name(t)) return t;
  return std::nullopt;
}

const std::vector<std::string>& platform_names() {
  static const std::vector<std::string> names = {"wheeled", "handheld", "legged"};
  return names;
}

}  // namespace tsgraphs::scene
