#pragma once
/// The storeys of a generated building (generator_storeys.cpp), drawn before generator.cpp
/// builds their walls, furniture and survey path: one wing of a style (with the lobby under an
/// atrium), mixed wings side by side, or storeys joined by ramps.
#include <string>
#include <vector>

#include "tsgraphs/generator/floor_plan.hpp"
#include "tsgraphs/generator/random.hpp"
#include "tsgraphs/scene/scene.hpp"

namespace tsgraphs::generator::internal {

constexpr double kSlabThickness = 0.3;  // m between a ceiling and the floor above

Polygon2 rect_polygon(const Vec2& lo, const Vec2& hi);

/// A storey being built: its plan and where its slab is.
struct Storey {
  std::string name;
  FloorPlan plan;
  Polygon2 slab;
  double ceiling = 3.0;
  bool walked = true;
};

struct Building {
  std::vector<Storey> storeys;
  std::vector<scene::Ramp> ramps;  ///< levels as storey indices
};

/// The storeys of a building of `style` (building_style_names()), scaled by `scale`.
Building draw_building(const std::string& style, double scale, bool realistic, Rng& rng);

}  // namespace tsgraphs::generator::internal
