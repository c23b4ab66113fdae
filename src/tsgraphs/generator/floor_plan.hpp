#pragma once
/// A storey as spaces that tile its footprint (rooms, corridor segments, halls, voids, ramp
/// wells), the doors between them and the furniture in them, turned into the scene format:
/// a wall on every boundary between two spaces (or between a space and the outside), a door
/// as an opening in it, a railing where a walkable space meets a void, an open joint where
/// two corridor segments meet, and one ground-truth room per walkable space measured to the
/// wall faces. Used by the building generator (generator.hpp); docs/generator.md states the
/// rules.
#include <string>
#include <vector>

#include "tsgraphs/generator/random.hpp"
#include "tsgraphs/scene/scene.hpp"

namespace tsgraphs::generator {

enum class SpaceKind {
  kRoom,      ///< a room: ground truth, reached through doors
  kCorridor,  ///< a corridor segment: ground truth; joins other segments through open joints
  kHall,      ///< a large room (open plan, library hall): ground truth
  kVoid,      ///< a hole in the slab (an atrium's void, a ramp's well seen from above): railings round it
  kRamp,      ///< a ramp's footprint on its lower level: walkable, no ground truth
  kShaft,     ///< a closed shaft or casing (walls all round, no door): not walkable, no ground truth
};

/// What furniture a space gets once its walls and doors are known (furnishing.hpp).
enum class Furnishing {
  kNone,
  kOffice,    ///< desks, shelves and cabinets against the walls
  kShelves,   ///< a library hall: rows of free-standing shelves with aisles
  kOpenPlan,  ///< desks in clusters, partitions lower than the ceiling, pillars
  kLobby,     ///< a few pillars and benches
};

struct Space {
  std::string name;
  SpaceKind kind = SpaceKind::kRoom;
  Polygon2 outline;  ///< wall centre lines, counter-clockwise
  Furnishing furnishing = Furnishing::kNone;
};

/// A door wanted between spaces a and b: placed on the longest straight stretch of their
/// common boundary, at `position` (0..1) of the stretch that leaves room for its jambs.
struct DoorSpec {
  int a = 0, b = 0;
  double width = 0.9;
  double position = 0.5;
};

struct FloorPlanRules {
  double interior_wall = 0.15;  ///< wall thickness between two spaces, m
  double exterior_wall = 0.25;  ///< facade thickness, m
  double door_height = 2.1;     ///< m
  double jamb = 0.25;     ///< m of wall kept between a door and the end of its stretch (beyond half a wall)
  double min_door = 0.8;  ///< m: a door narrower than this is not made
  scene::RailingStyle railing = scene::RailingStyle::kSolid;
  double railing_height = 1.0;      ///< m
  double glass_transmission = 0.8;  ///< share of rays a glass railing lets through
};

struct FloorPlan {
  std::vector<Space> spaces;
  std::vector<DoorSpec> doors;
  std::vector<std::pair<int, int>>
      open_joints;  ///< spaces joined with no wall (corridor segments, a ramp's foot)
  std::vector<std::pair<int, int>> no_railing;  ///< a void's edge walked over (a ramp's top edge)
  FloorPlanRules rules;
  bool ground_truth = true;  ///< false for a storey the path does not walk (an atrium's lower storey)
  bool realistic =
      false;  ///< generate --realistic: the styles add rows of small offices (building_styles.hpp)

  int add(const std::string& name, SpaceKind kind, const Polygon2& outline, Furnishing f = Furnishing::kNone);
  int add_rect(const std::string& name, SpaceKind kind, const Vec2& lo, const Vec2& hi,
               Furnishing f = Furnishing::kNone);
};

/// True for spaces that are ground truth (rooms, corridor segments, halls).
bool is_ground_truth(SpaceKind kind);
/// True for spaces one can walk in (not voids, not shafts).
bool is_walkable(SpaceKind kind);

/// The common boundary of two spaces: straight stretches, each with its ends.
struct SharedStretch {
  Vec2 a, b;
};
std::vector<SharedStretch> shared_boundary(const FloorPlan& plan, int a, int b);

/// Adds doors until every walkable space can be reached from every other through doors and
/// open joints: where two groups of spaces touch, a door on their longest common stretch,
/// preferring corridor to corridor, then corridor to room, then room to room.
void connect_spaces(FloorPlan* plan, Rng& rng);

/// A wall add_floor_plan made: its index in Scene::walls and the spaces on its two sides
/// (b = -1: the outside, a facade).
struct PlanWall {
  int wall = 0;
  int a = -1, b = -1;
};

/// What add_floor_plan made, for the generator's checks and the furniture.
struct PlanResult {
  std::vector<PlanWall> walls;     ///< every wall made, in Scene::walls order
  std::vector<int> room_of_space;  ///< index into scene.rooms, -1 for voids, ramps and unwalked storeys
  std::vector<Polygon2> faces;     ///< each space's outline measured to the faces of what bounds it
  int doors_made = 0;
  int doors_dropped = 0;  ///< doors that did not fit their boundary
};

/// Appends level `level`'s walls, openings, railings, voids and ground-truth rooms to `scene`
/// (the level itself, with its slab, must exist). Throws std::invalid_argument when spaces
/// overlap.
PlanResult add_floor_plan(const FloorPlan& plan, int level, scene::Scene* scene);

/// `poly` moved inwards by offsets[i] along each edge i (vertex i to i + 1); the offsets
/// are small against the edges.
Polygon2 inset_polygon(const Polygon2& poly, const std::vector<double>& offsets);

/// Counter-clockwise outline of the union of two axis-aligned rectangles stacked in y
/// ([a0, a1] x [y0, y1] below [b0, b1] x [y1, y2]) that overlap in x: an L, a T or a rectangle.
Polygon2 stacked_outline(double a0, double a1, double y0, double y1, double b0, double b1, double y2);

}  // namespace tsgraphs::generator
