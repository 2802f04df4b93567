// Who talks on a bus, in the Source and Destination columns: "master", "station 2".
#pragma once

#include <epan/packet.h>

#include <cstdint>

#include "plan/frame_record.h"

namespace pvtap::dissector {

// TalkerList: the talkers named so far in one column, each once, in the order they first
// talked. Plain data (texts in the packet's pool): the tree calls between its uses may longjmp.
struct TalkerList {
  const char* text = nullptr;
  bool master = false;
  std::uint8_t stations[32] = {};  // a bit per station address named
};

// TalkerColumns: the talkers of the frames a packet shows.
struct TalkerColumns {
  TalkerList source;
  TalkerList destination;
};

// Adds the talkers of `frame`: a request goes from "master" to "station N", a reply the other
// way. A frame whose header could not be read names no talker.
void add_talkers(TalkerColumns& columns, const FrameRecord& frame, wmem_allocator_t* pool);

// Writes the talkers into the link-layer source and destination columns, which the Source and
// Destination columns show unless the packet has network addresses (an exported PDU with
// address tags): Wireshark fills those columns from the addresses after dissection, so the
// addresses win.
void write_talkers(const TalkerColumns& columns, packet_info* pinfo);

}  // namespace pvtap::dissector
