#pragma once
/// The generator's building styles: each fills a rectangle of a storey with spaces (rooms,
/// corridor segments, halls, voids), the doors it wants and what furniture goes where. The
/// random ranges are named constants in each style's file; docs/generator.md lists them.
#include <string>
#include <vector>

#include "tsgraphs/generator/floor_plan.hpp"
#include "tsgraphs/generator/random.hpp"

namespace tsgraphs::generator {

/// An axis-aligned rectangle of a storey, [lo, hi].
struct Region {
  Vec2 lo = Vec2::Zero(), hi = Vec2::Zero();
  double width() const { return hi.x() - lo.x(); }
  double depth() const { return hi.y() - lo.y(); }
};

/// Rooms off one or more corridors (1.2-3.5 m wide): straight, bent or branching; rooms
/// 2.5-12 m, deep blocks in two rows (the back rooms entered through the front ones).
void fill_office(FloorPlan* plan, const Region& region, Rng& rng, const std::string& prefix);
/// A corridor ring round one void or two (a bridge between them), railings on the voids'
/// edges, rooms off the ring. The storey below is the caller's.
void fill_atrium(FloorPlan* plan, const Region& region, Rng& rng, const std::string& prefix);
/// Halls with rows of free-standing shelves, off a corridor that is narrow and then wide.
void fill_library(FloorPlan* plan, const Region& region, Rng& rng, const std::string& prefix);
/// One large hall (partitions lower than the ceiling, desks, pillars), meeting rooms off it.
void fill_open_plan(FloorPlan* plan, const Region& region, Rng& rng, const std::string& prefix);
/// One of: a diagonal corridor (30-60 degrees) with rooms whose walls meet it at that angle;
/// a pentagonal corridor ring round a room, irregular rooms in the corners; rooms in two rows
/// merged into L and T shapes.
enum class IrregularVariant { kAny, kDiagonal, kPentagon, kMergedRooms };
void fill_irregular(FloorPlan* plan, const Region& region, Rng& rng, const std::string& prefix,
                    IrregularVariant variant = IrregularVariant::kAny);

/// The smallest region (width, depth) each style fills well.
Vec2 minimum_region(const std::string& style);

// Helpers shared by the styles.

/// `length` cut into pieces each in [lo, hi] (as even as the randomness allows); one piece
/// when length < 2 lo.
std::vector<double> split_length(double length, double lo, double hi, Rng& rng);

/// Which side of a block faces its corridor.
enum class Side { kSouth, kNorth, kWest, kEast };

/// Fills the block [lo, hi] with rooms along `side` (widths 2.5-12 m), each wanting a door
/// to `corridor` (a space index, -1 for none); a block deeper than a room may be becomes two
/// rows, the back rooms wanting doors to the front ones. Returns the rooms' space indices.
std::vector<int> fill_block(FloorPlan* plan, const Region& block, Side side, int corridor, Rng& rng,
                            const std::string& prefix, Furnishing furnishing = Furnishing::kOffice);

/// A door wanted between a and b, 0.8-2.0 m wide (mostly about 1 m).
DoorSpec random_door(int a, int b, Rng& rng);

/// Mirrors the spaces from index `first` on about the region's centre lines (x when `mx`,
/// y when `my`), so that one layout comes in four orientations.
void mirror_spaces(FloorPlan* plan, int first, const Region& region, bool mx, bool my);

/// `poly` cut to the half plane n . (p - at) >= 0 (Sutherland-Hodgman, one plane).
Polygon2 clip_half_plane(const Polygon2& poly, const Vec2& at, const Vec2& n);

}  // namespace tsgraphs::generator
