// Registers the fields, expert infos and subtrees that every frame of a protocol may use.
#pragma once

#include "protocol/inverter_protocol.h"

namespace pvtap::dissector {

// Call after proto_register_protocol; fills protocol.hf, protocol.ei and protocol.ett.
void register_common_items(InverterProtocol& protocol);

}  // namespace pvtap::dissector
