// The platform measurement on scene files, cheaply: each scene simulated at the scans a run
// would measure (platform.scans spread over the run, levelled by the odometry's gravity, as a
// run with poses does), the sensor's height measured as the run does, against the scene's
// mount height. For the carriers suite's scenes (issue 16):
//   ./build/bench/bench_platform_estimate [--scans N] DIR/cases/*/scene.yaml
#include <cmath>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "tsgraphs/odometry/platform_estimate.hpp"
#include "tsgraphs/pipeline/pipeline_config.hpp"
#include "tsgraphs/scene/scene_loader.hpp"
#include "tsgraphs/sim/simulator.hpp"

using namespace tsgraphs;

int main(int argc, char** argv) {
  const pipeline::PipelineConfig defaults;
  odometry::PlatformEstimateConfig measure = defaults.platform.measure;
  int first = 1;
  if (argc > 2 && std::string(argv[1]) == "--scans") {
    measure.scans = std::stoi(argv[2]);
    first = 3;
  }
  if (argc <= first) {
    std::fprintf(stderr, "usage: %s [--scans N] SCENE.yaml...\n", argv[0]);
    return 2;
  }
  std::printf("| scene | mount (m) | measured (m) | error (m) | floors |\n|---|---|---|---|---|\n");
  double worst = 0.0;
  for (int a = first; a < argc; ++a) {
    try {
      const scene::Scene scene = scene::load_scene(argv[a]);
      const sim::Simulator sim(scene, scene.seed);
      const std::size_t total = sim.num_scans(), n = static_cast<std::size_t>(measure.scans);
      std::vector<PointCloud> scans;
      std::vector<Eigen::Vector3d> ups;
      for (std::size_t j = 0; j < n; ++j) {
        const std::size_t k = n == 1 ? 0 : j * (total - 1) / (n - 1);
        scans.push_back(sim.scan(k));
        ups.push_back(sim.odometry_poses()[k].linear().transpose() * Eigen::Vector3d::UnitZ());
      }
      const odometry::PlatformEstimate e =
          odometry::estimate_platform(scans, defaults.floor_levelling, measure, ups);
      const double mount = scene.sensor.mount_height;
      const double err = e.height_found ? e.height - mount : NAN;
      worst = std::max(worst, e.height_found ? std::abs(err) : INFINITY);
      std::printf("| %s | %.2f | %.3f | %+.3f | %zu of %zu |\n", argv[a], mount, e.height, err,
                  e.floors_found, e.scans_measured);
    } catch (const std::exception& ex) {
      std::fprintf(stderr, "%s: %s\n", argv[a], ex.what());
      return 2;
    }
  }
  std::printf("\nworst |error|: %.3f m\n", worst);
  return 0;
}
