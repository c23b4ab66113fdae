#pragma once
/// The two kinds of space the room layer extracts and the graph holds a node for: shared by
/// rooms/ (which finds them) and graph/ (which optimises them), so neither includes the other.
#include <string>

namespace tsgraphs {

enum class RoomKind { room, corridor };

/// "room" or "corridor".
inline std::string to_string(RoomKind kind) { return kind == RoomKind::room ? "room" : "corridor"; }

}  // namespace tsgraphs
