#include "tsgraphs/eval/room_support.hpp"

#include <algorithm>
#include <map>
#include <string>

#include "tsgraphs/scene/scene_geometry.hpp"

namespace tsgraphs::eval {
namespace {

// The rectangle of a strip `width` wide along the segment [a, b].
Polygon2 strip(const Vec2& a, const Vec2& b, double width) {
  const Vec2 d = b - a;
  const double length = d.norm();
  if (length <= 0.0) return {};
  const Vec2 n = Vec2(-d.y(), d.x()) * (0.5 * width / length);
  return {a - n, b - n, b + n, a + n};
}

// The cells of `level` that something standing on the floor occupies: the wall pieces that
// start at the floor (a lintel over a door is walked under) and the railings.
std::vector<CellKey> blocked_cells(const scene::Scene& scene, int level) {
  std::vector<CellKey> cells;
  auto add = [&](const Polygon2& polygon) {
    const std::vector<CellKey> c = raster_cells(polygon);
    cells.insert(cells.end(), c.begin(), c.end());
  };
  for (const scene::Wall& w : scene.walls) {
    if (w.level != level) continue;
    const double length = (w.to - w.from).norm();
    if (length <= 0.0) continue;
    const Vec2 u = (w.to - w.from) / length;
    for (const scene::WallPiece& p : scene::wall_pieces(w)) {
      if (p.z0 == 0.0) add(strip(w.from + p.s0 * u, w.from + p.s1 * u, w.thickness));
    }
  }
  for (const scene::Railing& r : scene.railings) {
    if (r.level != level) continue;
    const double width = r.style == scene::RailingStyle::kBars ? scene::RailingGeometry::kPostWidth
                                                               : scene::RailingGeometry::kSolidThickness;
    add(strip(r.from, r.to, width));
  }
  std::sort(cells.begin(), cells.end());
  cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
  return cells;
}

double share(std::size_t unwalkable, std::size_t cells) {
  return cells == 0 ? 0.0 : static_cast<double>(unwalkable) / static_cast<double>(cells);
}

}  // namespace

std::vector<double> unwalkable_shares(const std::vector<LevelFootprint>& rooms, const scene::Scene& scene) {
  std::map<int, std::vector<CellKey>> blocked;  // per level index, made when a room needs it
  std::vector<double> shares;
  for (const LevelFootprint& room : rooms) {
    const std::vector<CellKey> cells = raster_cells(room.polygon);
    int level = -1;
    for (std::size_t i = 0; i < scene.levels.size(); ++i)
      if (scene.levels[i].name == room.level) level = static_cast<int>(i);
    if (level < 0) {
      shares.push_back(share(cells.size(), cells.size()));
      continue;
    }
    auto it = blocked.find(level);
    if (it == blocked.end()) it = blocked.emplace(level, blocked_cells(scene, level)).first;
    std::size_t unwalkable = 0;
    for (const CellKey c : cells) {
      double z = 0.0;
      if (!scene::walkable_height(scene, level, cell_center(c), &z) ||
          std::binary_search(it->second.begin(), it->second.end(), c))
        ++unwalkable;
    }
    shares.push_back(share(unwalkable, cells.size()));
  }
  return shares;
}

std::vector<double> unwalkable_shares(const std::vector<LevelFootprint>& rooms,
                                      const std::vector<io::RoomTruth>& truth) {
  std::map<std::string, std::vector<CellKey>> walkable;  // per level: the union of its true rooms
  for (const io::RoomTruth& t : truth) {
    std::vector<CellKey>& level = walkable[t.level];
    level = cell_union(level, raster_cells(t.polygon));
  }
  std::vector<double> shares;
  for (const LevelFootprint& room : rooms) {
    const std::vector<CellKey> cells = raster_cells(room.polygon);
    const auto it = walkable.find(room.level);
    const std::size_t inside = it == walkable.end() ? 0 : shared_cells(cells, it->second);
    shares.push_back(share(cells.size() - inside, cells.size()));
  }
  return shares;
}

RoomSupport room_support(const std::vector<double>& unwalkable_shares) {
  RoomSupport s;
  for (const double share : unwalkable_shares) {
    if (share > kMaxUnwalkableShare) ++s.unsupported;
    s.max_unwalkable_share = std::max(s.max_unwalkable_share.value_or(0.0), share);
  }
  return s;
}

}  // namespace tsgraphs::eval
