#include "tsgraphs/rooms/room.hpp"

namespace tsgraphs::rooms {

std::string to_string(RoomKind kind) { return kind == RoomKind::room ? "room" : "corridor"; }

}  // namespace tsgraphs::rooms
