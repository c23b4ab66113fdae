#pragma once
/// What the run folder's writer and readers share (run_folder_writer.cpp, run_folder_reader.cpp,
/// run_folder_timings_reader.cpp, run_folder_map_reader.cpp): timings.csv's columns and the
/// readers' way of naming a bad value.
#include <cstddef>
#include <stdexcept>
#include <string>

namespace tsgraphs::io::run_folder_internal {

constexpr const char* kTimingsHeader =
    "kind,index,stamp,keyframe,num_points,prefilter_ms,walls_ms,loop_ms,frontend_ms,"
    "optimization_s,full,n_variables,n_factors,iterations,reason,"
    "ground_ms,ground_nodes,ground_tp,ground_fp,ground_fn,rooms_ms";
// Columns added later: read when present (older run folders lack them).
constexpr const char* kActiveKeyframes = "active_keyframes";

// What is wrong with one value, named by its key path ('rooms[2].rect.size'); the caller adds
// the file and, for line-based files, the line.
struct FieldError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// The text of a run folder's file; a folder or a missing file is an InputError naming it.
std::string read_text(const std::string& path);

/// `parent[i]`, a key path's element.
std::string item(const std::string& parent, std::size_t i);

/// A value in metres of the map (or a unit vector's or quaternion's component): finite and
/// within kMaxCoordinate, else a FieldError naming it.
double bounded_coordinate(double x, const std::string& name);

}  // namespace tsgraphs::io::run_folder_internal
