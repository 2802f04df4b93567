// The preferences of each protocol: checks, reassembly, reply timeout, the reference's options.
#pragma once

#include "protocol/inverter_protocol.h"

namespace pvtap::dissector {

// Registers the protocol's preference module; call at protocol registration.
void register_preferences(InverterProtocol& protocol);

// Puts the current preference values to work (the register decoder's options).
void apply_preferences();

}  // namespace pvtap::dissector
