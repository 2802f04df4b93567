// Shows a decided piece of a bus (frame or noise run) or a timeout announcement in the tree.
#pragma once

#include <epan/packet.h>

#include <cstdint>
#include <span>

#include "stream/bus_track.h"
#include "tree/frame_tree.h"

namespace pvtap::dissector {

// PieceTarget: the packet a piece is shown in, and what the call knows of its bus.
struct PieceTarget {
  tvbuff_t* tvb = nullptr;  // holds the piece's bytes at `offset`
  packet_info* pinfo = nullptr;
  proto_tree* tree = nullptr;
  InverterProtocol* bound = nullptr;  // the protocol the call was made for
  BusTrack* bus = nullptr;
};

// Shows `piece`, whose bytes are `bytes`, at `offset` of target.tvb: a frame under the protocol
// of its dialect, noise under the protocol whose frames it resembles.
void show_piece(const PieceTarget& target, const BusPiece& piece,
                std::span<const std::uint8_t> bytes, int offset);

// Shows a frame whose record the bus decided, at target.offset of target.tvb, under
// target.protocol (a Modbus/TCP ADU's station byte and PDU).
void show_frame(const TreeTarget& target, std::span<const std::uint8_t> bytes, FrameRecord& record);

// Shows bytes the bus decided are no frame, at target.offset of target.tvb, under the
// protocol whose frames they resemble (target.protocol, or invascii).
void show_noise(const TreeTarget& target, std::span<const std::uint8_t> bytes);

// Shows the announcement that `request` got no reply, under the protocol of its dialect.
void show_timeout(const FrameRecord& request, tvbuff_t* tvb, packet_info* pinfo, proto_tree* tree);

// Announces a collision the bus's session named: an expert info of invrtu (collisions belong
// to no dialect), "collision" in Info.
void show_collision(const SessionCollision& collision, tvbuff_t* tvb, packet_info* pinfo,
                    proto_tree* tree);

// The number of this call of `proto` for the packet, from 1 (TCP may call more than once).
guint32 next_call_number(packet_info* pinfo, int proto);

}  // namespace pvtap::dissector
