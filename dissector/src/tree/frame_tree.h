// Puts a tree description into Wireshark's protocol tree.
#pragma once

#include <epan/packet.h>

#include "protocol/inverter_protocol.h"
#include "tree/tree_description.h"

namespace pvtap::dissector {

// TreeTarget: where one piece (frame or noise) lies and which tree it goes to.
struct TreeTarget {
  tvbuff_t* tvb = nullptr;
  packet_info* pinfo = nullptr;
  proto_tree* tree = nullptr;
  int offset = 0;
  int length = 0;
  InverterProtocol* protocol = nullptr;
};

// Adds the described items with the protocol's field, expert and subtree ids. The
// description is plain data in pinfo->pool: Wireshark may throw (longjmp) out of any call
// made here.
void add_tree(const TreeTarget& target, const TreeDescription& description);

}  // namespace pvtap::dissector
