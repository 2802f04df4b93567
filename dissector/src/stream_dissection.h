// Cuts the bytes one transport delivered into frames and noise and dissects each piece.
#pragma once

#include <epan/packet.h>

#include "bus_matcher.h"
#include "inverter_protocol.h"

namespace pvtap::dissector {

// StreamContext: what the transport knows about the bytes it hands over.
struct StreamContext {
  InverterProtocol* protocol = nullptr;
  BusMatcher* matcher = nullptr;      // the bus these bytes belong to
  RoleHint hint = RoleHint::Unknown;  // who sent them, when the transport knows
  bool desegment = false;             // TCP: a frame cut by the segment end waits for more
};

// Dissects every frame and noise run of `tvb`; with desegment set, the bytes of a frame that
// runs past the end are handed back to TCP to be completed by the next segments. Returns the
// number of bytes taken (all of them).
int dissect_stream(tvbuff_t* tvb, packet_info* pinfo, proto_tree* tree, const StreamContext& ctx);

}  // namespace pvtap::dissector
