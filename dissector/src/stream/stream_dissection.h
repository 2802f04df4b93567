// Shows the frames and noise runs the core decided in the bytes one transport delivered.
#pragma once

#include <epan/packet.h>

#include "protocol/inverter_protocol.h"
#include "stream/bus_track.h"

struct tcpinfo;

namespace pvtap::dissector {

// StreamContext: what the transport knows about the bytes it hands over.
struct StreamContext {
  InverterProtocol* protocol = nullptr;  // the protocol the conversation is bound to
  BusTrack* bus = nullptr;               // the bus these bytes belong to
  Direction direction = Direction::Unknown;
  const tcpinfo* tcp = nullptr;  // TCP: the segment's sequence numbers; null for datagrams
  bool desegment = false;        // TCP: undecided bytes wait for the next segment
  // Exported-PDU records: the Source and Destination columns name the frames' talkers
  // ("master", "station 2") where the record has no addresses of its own.
  bool names_talkers = false;
};

// Shows every piece of `tvb` the bus decided, each frame under the protocol of its dialect;
// with desegment set, the undecided rest is handed back to TCP to come again with the next
// segment. Returns the number of bytes taken (all of them).
int dissect_stream(tvbuff_t* tvb, packet_info* pinfo, proto_tree* tree, const StreamContext& ctx);

}  // namespace pvtap::dissector
