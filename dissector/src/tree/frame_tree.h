// Puts a planned frame, or a run of noise, into the protocol tree.
#pragma once

#include <epan/packet.h>

#include <optional>

#include "plan/frame_plan.h"
#include "plan/frame_record.h"
#include "pvtap/codec/unknown_function_frame.h"
#include "registration/inverter_protocol.h"

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

// Adds the frame's subtree, its expert infos and its links to the matching frames. Uses only
// plain data: Wireshark may throw (longjmp) out of any call made here.
void add_frame_tree(const TreeTarget& target, const FramePlan& plan, const FrameRecord& record);

// Adds a noise item; `unknown` is set when the noise is a whole frame of an unknown function.
void add_noise_tree(const TreeTarget& target, const std::optional<UnknownFunctionFrame>& unknown);

}  // namespace pvtap::dissector
