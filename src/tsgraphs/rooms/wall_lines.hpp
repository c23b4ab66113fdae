#pragma once
/// The room segmentation's walls (room_segmentation.cpp): the level's walls as lines at floor
/// height, and the segments that close the doors and the openings between them, drawn into the
/// raster as blocked cells. Internal to the rooms module.
#include <utility>
#include <vector>

#include "tsgraphs/core/grid_frame.hpp"
#include "tsgraphs/rooms/room_segmentation.hpp"

namespace tsgraphs::rooms::segmentation_steps {

/// Cells between the samples that draw or walk a line: the line stays 8-connected.
inline constexpr double kLineStep = 0.5;

/// The wall's line at floor height: unit normal n (as the plane's, horizontal) and offset d.
struct WallLine {
  int id = -1;
  Vec2 n = Vec2::UnitX();
  double d = 0.0;
  Vec2 a = Vec2::Zero(), b = Vec2::Zero();  ///< its extent, on the line
};

WallLine line_at(const WallCandidate& w, double floor_z);
/// A vertical plane of min_wall_height of this level (of_level's comment in wall_lines.cpp).
bool of_level(const WallCandidate& w, double floor_z, const RoomSegmentationConfig& cfg);
/// The walls of the level as lines at floor height (with `reaching`, only those that bound spaces).
std::vector<WallLine> level_walls(const std::vector<WallCandidate>& walls, double floor_z,
                                  const RoomSegmentationConfig& cfg, bool reaching = true);
/// The openings closed between the level's walls that lie on one straight line.
std::vector<std::pair<Vec2, Vec2>> line_openings(const std::vector<WallLine>& walls,
                                                 const RoomSegmentationConfig& cfg);
/// The segments that close the doors.
std::vector<std::pair<Vec2, Vec2>> door_closures(const std::vector<WallLine>& walls,
                                                 const RoomSegmentationConfig& cfg);
/// The cells of the segment a-b marked in `blocked`.
void draw_line(const GridFrame& f, const Vec2& a, const Vec2& b, std::vector<std::uint8_t>* blocked);

}  // namespace tsgraphs::rooms::segmentation_steps
