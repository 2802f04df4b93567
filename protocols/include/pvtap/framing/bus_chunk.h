// Bytes as the capture path delivers them: a chunk, its time and the direction it came from.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "pvtap/codec/dialect.h"

namespace pvtap {

// Direction: what the capture path knows about who sent a chunk.
enum class Direction : std::uint8_t { Unknown = 0, ToSlave = 1, FromSlave = 2 };

// The directions, as indexes of per-direction tables.
inline constexpr std::size_t kDirections = 3;
constexpr std::size_t index_of(Direction d) {
  return static_cast<std::size_t>(d);
}

// What a direction says about the role of the frames in it.
constexpr RoleHint role_hint(Direction d) {
  switch (d) {
    case Direction::ToSlave:
      return RoleHint::Request;
    case Direction::FromSlave:
      return RoleHint::Response;
    default:
      return RoleHint::Unknown;
  }
}

// The direction whose frames play the role `hint` says (the inverse of role_hint).
constexpr Direction direction_of(RoleHint hint) {
  switch (hint) {
    case RoleHint::Request:
      return Direction::ToSlave;
    case RoleHint::Response:
      return Direction::FromSlave;
    default:
      return Direction::Unknown;
  }
}

// BusChunk: bytes as one read delivered them; `time` is the capture time of the last byte.
struct BusChunk {
  std::span<const std::uint8_t> bytes;
  double time = 0.0;
  Direction direction = Direction::Unknown;
  // False when the other direction's last bytes may still be on their way (a TCP hole
  // waiting for a retransmission): this chunk does not end that direction's turn.
  bool previous_turn_complete = true;
};

}  // namespace pvtap
