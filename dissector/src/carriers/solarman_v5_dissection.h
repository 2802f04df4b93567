// Shows the V5 frames the core's reader decided in the bytes TCP delivered, each RTU frame
// inside handed to invrtu on the conversation's bus.
#pragma once

#include <epan/packet.h>

#include "carriers/solarman_v5_track.h"

struct tcpinfo;

namespace pvtap::dissector {

// V5Context: what TCP knows of the bytes it hands over.
struct V5Context {
  SolarmanV5Track* track = nullptr;
  Direction direction = Direction::Unknown;
  const tcpinfo* tcp = nullptr;
  bool desegment = false;  // undecided bytes wait for the next segment
};

// Shows every V5 piece of `tvb` the reader decided; with desegment set, the undecided rest is
// handed back to TCP to come again with the next segment. Returns the bytes taken (all).
int dissect_v5_stream(tvbuff_t* tvb, packet_info* pinfo, proto_tree* tree, const V5Context& ctx);

}  // namespace pvtap::dissector
