#pragma once
/// `segment-map`: the room segmentation of a 2-D occupancy map (docs/segment-map.md), as
/// ipa_room_segmentation and ROSE2 offer it offline: map in, one colour per room out, and with
/// the true rooms the IPA figures and room F1 over the whole map.
#include <string>

namespace tsgraphs::app {

struct SegmentMapOptions {
  std::string map;      ///< the map_server YAML
  std::string out;      ///< label image to write (PNG, one colour per room, black none)
  std::string rooms;    ///< true room labels (IPA or one colour per room), or ""
  std::string config;   ///< parameter file (room_segmentation, map_walls, free_space sections), or ""
  std::string metrics;  ///< JSON file for the figures, or ""
  bool quiet = false;
};

/// Segments the map, writes the label image (and the figures), prints a summary line and, with
/// true rooms, the figures. Bad input is an InputError; nothing is written then.
void segment_map(const SegmentMapOptions& options);

}  // namespace tsgraphs::app
