// The ways TCP bytes reach invv5: its heuristic, which recognises a stick's flow by the
// structure of its first frame, and its dissector for the conversation it then binds.
#pragma once

#include <epan/packet.h>

#include "wireshark_api/heuristic_verdict.h"

namespace pvtap::dissector {

int dissect_v5_tcp(tvbuff_t* tvb, packet_info* pinfo, proto_tree* tree, void* data);

HeuristicVerdict v5_tcp_heuristic(tvbuff_t* tvb, packet_info* pinfo, proto_tree* tree, void* data);

}  // namespace pvtap::dissector
