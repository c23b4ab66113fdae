#include "tsgraphs/report/scene_svg.hpp"

namespace tsgraphs::report {

std::string scene_svg(const sim::Scene& scene, const sim::Trajectory&) {
  return "<svg xmlns=\"http://www.w3.org/2000/svg\"><title>" + scene.name + "</title></svg>\n";
}

}  // namespace tsgraphs::report
