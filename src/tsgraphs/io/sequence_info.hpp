#pragma once
/// Everything of a sequence but its scans: times, odometry, and the simulator's ground truth.
#include <string>
#include <utility>
#include <vector>

#include "tsgraphs/core/polygon.hpp"
#include "tsgraphs/core/pose.hpp"

namespace tsgraphs::io {

/// A ground-truth room of rooms_gt.json.
struct RoomTruth {
  std::string name;
  std::string level;  ///< the level's name
  Polygon2 polygon;
  double elevation = 0.0;  ///< the level's floor height
};

/// Everything of a sequence but the scans.
struct SequenceInfo {
  std::vector<double> times;       ///< one per scan
  std::vector<Pose3> odometry;     ///< one per scan, sensor in odom frame
  std::vector<Pose3> groundtruth;  ///< empty, or one per scan
  std::vector<double> lap_starts;  ///< empty, or the start time of each lap
  bool has_rooms = false;          ///< write / found rooms_gt.json
  std::vector<RoomTruth> rooms;
  std::string scene_yaml;  ///< copied to scene.yaml when not empty
  /// Files the scene needs (its voxel maps), copied into the folder: source path, and the
  /// path inside the folder that scene_yaml names.
  std::vector<std::pair<std::string, std::string>> attached_files;
};

}  // namespace tsgraphs::io
