// Registers the fields, expert infos and subtrees of the plain Modbus functions (invrtu).
#pragma once

#include "protocol/inverter_protocol.h"

namespace pvtap::dissector {

// Call after register_common_items; fills protocol.hf.modbus and the Modbus experts.
void register_modbus_items(InverterProtocol& protocol);

}  // namespace pvtap::dissector
