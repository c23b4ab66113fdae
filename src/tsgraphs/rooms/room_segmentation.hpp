#pragma once
/// Room segmentation of the free space walked (TS-graphs' room layer): a room or corridor
/// segment is the space one can walk in, bounded by what stops one walking.
///
/// On a raster of one level:
/// 1. the *free space* is the union of the discs of radius lambda round the free-space vertices
///    (each vertex is at least lambda from every obstacle, so its disc is clear): the
///    traversable ground opened by the robot's size, off voids, walls and furniture;
/// 2. every mapped wall is drawn across it along its whole extent, and on to the next wall
///    where it ends within a door's width of one, so a door (an opening in a wall, or between
///    a wall's end and the wall it meets) is closed and a wall the free space does not cross
///    bounds it;
/// 3. the spaces are the parts of what is left (with what the sensor's rays crossed at walking
///    height over a floor, freespace/sight_map.hpp, and the traversable ground) that only
///    narrowings join (rooms/narrowings.hpp: a watershed of the clearance, so a door is found
///    whether or not its posts were mapped); a space the robot does not fit in goes, one too
///    small to be a room joins the one it opens to; a corridor (long for its width) is cut
///    into its straight legs at its inner corners;
/// 4. a region's footprint is its outer outline, or its smallest enclosing rectangle where it
///    fills that rectangle (sides on the walls beside them: the room-planes factor's planes).
/// Only what the free space carries becomes a footprint: a void, the slab's outside or the
/// inside of a wall never does, whatever the planes around it.
#include <vector>

#include "tsgraphs/core/grid_frame.hpp"
#include "tsgraphs/rooms/room.hpp"
#include "tsgraphs/core/config_fields.hpp"

namespace tsgraphs::rooms {

struct RoomSegmentationConfig {
  double cell = 0.1;
  double max_normal_z = 0.2;
  double min_wall_height = 1.0;
  double wall_reach_height = 2.3;
  double wall_top_margin = 0.2;
  double wall_top_beyond = 0.2;
  double wall_top_share = 0.25;
  double wall_joint_gap = 0.4;
  double max_door_width = 2.0;
  double door_narrowing = 0.7;
  double min_door_post = 0.8;
  double opening_share = 1.0;
  double line_tolerance = 0.15;
  double min_region_area = 2.0;
  double rect_fill = 0.85;
  double wall_snap = 0.4;
  double parallel_tolerance_deg = 10.0;
  double min_wall_overlap = 0.3;
  double corridor_aspect = 3.0;
  double max_corridor_width = 5.0;
  double simplify_tolerance = 0.15;
  double bend_tolerance = 0.3;
  double min_bend_deg = 45.0;
  double min_fit_share = 0.5;
  double frontier_reach = 0.3;

  template <class V>
  void visit(V& v) {
    v("cell", cell, between(0.02, 10.0),
      "raster cell (m): an eighth of the narrowest door, finer than the node map");
    v("max_normal_z", max_normal_z, between(0.0, 0.99), "|n.z| above this: not a vertical plane, no wall");
    v("min_wall_height", min_wall_height, between(0.0, 100.0),
      "lower planes are desks and tables, not walls (m); a plane short of wall_reach_height bounds only if "
      "no ray saw above its top");
    v("wall_reach_height", wall_reach_height, between(0.0, 100.0),
      "a wall bounds a level when its points span this height above the floor (m), or no ray saw above its "
      "top (wall_top_*): above a door's lintel and the tallest furniture (shelves end by 2.2 m), below the "
      "ceiling; a lintel, the storey above, a shelf row or a railing does not");
    v("wall_top_margin", wall_top_margin, between(0.0, 100.0),
      "a ray this far above a plane's highest point over its line saw above it (m)");
    v("wall_top_beyond", wall_top_beyond, between(0.0, 100.0),
      "...if it ends at least this far past the plane's line (m): not on its face");
    v("wall_top_share", wall_top_share, above(0.0, 1.0),
      "...along this share of its length: its top is seen (a shelf, a partition), it bounds a level only if "
      "it spans wall_reach_height; an unseen top (a low sensor sees a wall's foot) may reach the ceiling: it "
      "bounds the level");
    v("wall_joint_gap", wall_joint_gap, between(0.0, 100.0),
      "...if one of its ends is this close to another wall of the level, across it (a corner, a T; m): walls "
      "join into one structure, a free-standing shelf row or screen one walks round does not; two walls that "
      "would cross within this of both their ends meet at a corner (both mapped short of it: it is closed)");
    v("max_door_width", max_door_width, between(0.0, 100.0),
      "a wall that ends this close to another wall has a door (or an opening) between them: it is drawn on "
      "to it (m)");
    v("door_narrowing", door_narrowing, between(0.0, 1.0),
      "spaces meeting where the clearance is at most this share of the smaller one's widest clearance (and "
      "at most max_door_width / 2) meet at a door (rooms/narrowings)");
    v("min_door_post", min_door_post, between(0.0, 100.0),
      "...when it is at least this long, and so is a wall it meets across (m): a pillar's face is no wall to "
      "close a gap to; a wall in line with it (a pier between two doors) is a door post whatever its length");
    v("opening_share", opening_share, between(0.0, 1.0),
      "walls on one line (within line_tolerance) also close the openings between them narrower than this "
      "share of the length they cover: a wide opening in a long wall (a corridor's side past a bay, a "
      "facade's gaps where a laser saw through glass); at 1, a line with more wall than the opening is a "
      "wall (ROSE2's wall share of a layout's edge); a gap whose two ends lie on walls passing through the "
      "line (wall_joint_gap) spans the space between them, a corridor between two rows of rooms: open");
    v("line_tolerance", line_tolerance, between(0.0, 10.0),
      "walls whose ends lie this close to one line are on it: one wall seen in pieces, a row of rooms (m)");
    v("min_region_area", min_region_area, between(0.0, 1e6),
      "m^2: a smaller region (a doorway's strip between a wall's two faces, a corner square cut off) is no "
      "space of its own: it joins the one it opens to");
    v("rect_fill", rect_fill, above(0.0, 1.0),
      "a region filling this share of its smallest enclosing rectangle has it as footprint (else its "
      "outline)");
    v("wall_snap", wall_snap, between(0.0, 100.0),
      "a rectangle's side this near a parallel wall facing into it lies on the wall (m): the grown free "
      "space stops up to a node cell and a raster cell short of it");
    v("parallel_tolerance_deg", parallel_tolerance_deg, between(0.0, 89.0),
      "a wall is parallel to a side within this");
    v("min_wall_overlap", min_wall_overlap, between(0.0, 1.0),
      "...and runs along at least this share of the side");
    v("corridor_aspect", corridor_aspect, between(1.0, 1e6),
      "a region this many times longer than wide is a corridor segment");
    v("max_corridor_width", max_corridor_width, between(0.0, 1e6),
      "...and a region cut at its bends only if no wider than this (m; twice its largest clearance): "
      "corridors are 1.2-4 m wide, and at a corner or a junction the clearance is up to 1.3 times half "
      "that; a longer, wider space (a hall, a long room with furniture along it) is whole");
    v("simplify_tolerance", simplify_tolerance, between(0.0, 100.0),
      "an outline strays at most this from the region's cell edges (m)");
    v("bend_tolerance", bend_tolerance, between(0.0, 100.0),
      "a corridor's outline, for finding its bends, strays at most this (m): a chair's or a door jamb's "
      "notch is no bend");
    v("min_bend_deg", min_bend_deg, above(0.0, 179.0),
      "a corridor's inner corner turning at least this is a bend it is cut at");
    v("min_fit_share", min_fit_share, between(0.0, 100.0),
      "a region narrower everywhere than this share of the robot's width (2 lambda) is no space: a strip "
      "past a wall's line");
    v("frontier_reach", frontier_reach, between(0.0, 100.0),
      "rays end on a wall's face short of a space grown to its line: an unseen strip this wide (m) at a "
      "region's edge is no frontier");
  }
};

/// One level's free space and walls.
struct SegmentationInput {
  GridFrame frame;  ///< the raster (resolution = config.cell); empty: round the points
  std::vector<std::uint8_t>
      seen;  ///< per cell of frame (or empty): rays passed there at walking height over a floor
  std::vector<std::uint8_t>
      known;  ///< per cell of frame (or empty): any ray passed or ended there (no frontier)
  std::vector<Vec2> free_space;  ///< free-space vertices (at least free_radius from every obstacle)
  std::vector<Vec2> ground;      ///< every traversable node of the level (free or not)
  std::vector<Vec2> raised;  ///< traversable nodes above the level's floor but below its headroom (a ramp,
                             ///< a stair): the floor is not the level's there, whatever the rays passed over
  double free_radius = 0.4;  ///< the free space's lambda_th (m)
  double ground_radius = 0.25;  ///< a traversable node covers the disc of this radius (its node map cell, m)
  double floor_z = 0.0;         ///< the level's floor height, map frame (m)
  std::vector<WallCandidate> walls;  ///< mapped planes (others than vertical walls of this level are skipped)
  /// Every walkable cell belongs to a space: those none holds (rays seen through a door, pockets
  /// too thin or small to be spaces) join the nearest. A map's free cells are all some room's floor
  /// (segment-map); online, cells left out are the layer's doubt and stay out.
  bool label_every_cell = false;

  /// Widens [lo, hi] to hold the free-space vertices and the ground nodes.
  void extend_bounds(Vec2* lo, Vec2* hi) const;
};

/// A space found: its footprint and, where its rectangle's sides lie on walls, their planes.
struct SegmentedSpace {
  ExtractedRoom room;     ///< kind, rect (and outline when it is no rectangle), wall_ids for the factor
  double area = 0.0;      ///< of the region's cells (m^2)
  double frontier = 0.0;  ///< share of its edge cells beside what nothing has seen (0 without `known`): not
                          ///< yet explored there, so its footprint may still grow
  Vec2 centroid = Vec2::Zero();  ///< of the footprint
};

struct RoomSegmentation {
  GridFrame frame;
  std::vector<int> label;  ///< per cell: index into spaces, -1 for none
  std::vector<SegmentedSpace> spaces;

  /// The space holding `p`, else the one of the nearest labelled cell within `radius` (m), else -1.
  int space_at(const Vec2& p, double radius = 0.0) const;
};

/// Whether `wall` is a vertical plane of the level at floor_z (min_wall_height tall, coming down
/// to it) whose points do not span wall_reach_height: it bounds the level only if no ray saw
/// above its top (WallCandidate::top_seen) and it joins a wall that bounds.
bool short_of_reach(const WallCandidate& wall, double floor_z, const RoomSegmentationConfig& config);

/// Whether the step from `a` to `b` (floor points of the level at floor_z) crosses one of the
/// walls that bound its spaces (the same walls segment_rooms draws): the robot went through a
/// door or an opening in a wall, into another space.
bool crosses_wall(const Vec2& a, const Vec2& b, const std::vector<WallCandidate>& walls, double floor_z,
                  const RoomSegmentationConfig& config = {});

/// Segments one level (check_config first). Deterministic: the same input gives the same spaces in the
/// same order (by their first cell).
RoomSegmentation segment_rooms(const SegmentationInput& input, const RoomSegmentationConfig& config = {});

}  // namespace tsgraphs::rooms
