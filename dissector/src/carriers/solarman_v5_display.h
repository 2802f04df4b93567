// Shows one decided V5 piece in the tree: a frame with its header, payload fields and checksum
// verdict (its RTU frame handed to invrtu), a broken frame, or bytes that are no V5 frame.
#pragma once

#include <epan/packet.h>

#include <cstdint>
#include <span>

#include "carriers/solarman_v5_track.h"

namespace pvtap::dissector {

// V5Target: the packet a piece is shown in, and the conversation's track.
struct V5Target {
  tvbuff_t* tvb = nullptr;  // holds the piece's bytes at `offset`
  packet_info* pinfo = nullptr;
  proto_tree* tree = nullptr;
  SolarmanV5Track* track = nullptr;
  Direction direction = Direction::Unknown;
};

// `bytes` are the piece's, copied out of target.tvb, where they lie at `offset`.
void show_v5_piece(const V5Target& target, const V5Piece& piece,
                   std::span<const std::uint8_t> bytes, int offset);

}  // namespace pvtap::dissector
