#pragma once
/// The scans `run` and `convert` read: a sequence folder, a folder of scans, or a bag, with
/// their poses' source (--odometry) and the parameter file.
#include <CLI/CLI.hpp>
#include <memory>
#include <string>
#include <vector>

#include "tsgraphs/ros1_bag/ros_bag.hpp"
#include "tsgraphs/io/scan_folder.hpp"
#include "tsgraphs/pipeline/odometry_choice.hpp"
#include "tsgraphs/pipeline/pipeline_config.hpp"

namespace tsgraphs::app::cli {

struct ScanSourceOptions {
  std::string seq;
  io::ScanFolderOptions folder;        ///< a folder of scans instead of a sequence folder
  io::BagOptions bag;                  ///< a bag instead of a sequence folder
  std::vector<double> sensor_to_base;  ///< x y z qx qy qz qw
  std::string odometry = "auto";       ///< auto, input or lidar
  std::string config;                  ///< parameter file
  std::string out;                     ///< the command's output folder
};

/// The options of the scan source, the parameter file and --out (`out_help`) on `cmd`.
void add_scan_source_options(CLI::App& cmd, ScanSourceOptions& options, const std::string& out_help);

/// The scans opened and checked, the parameters loaded, and where the poses come from.
struct ScanSource {
  std::unique_ptr<io::ScanSequence> sequence;
  pipeline::PipelineConfig config;
  pipeline::OdometryOptions odometry;
};

/// Opens what `options` name for `command` (run or convert): one source, an output apart from
/// every input, a mount that is one; an InputError otherwise.
ScanSource open_scan_source(ScanSourceOptions& options, const std::string& command, bool quiet);

}  // namespace tsgraphs::app::cli
