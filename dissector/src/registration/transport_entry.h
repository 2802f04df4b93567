// The ways bytes reach a protocol: TCP and UDP (ports and heuristics), its named dissector,
// and Decode As for RTAC serial payloads.
#pragma once

#include "protocol/inverter_protocol.h"

namespace pvtap::dissector {

// Creates the protocol's handles and registers its named dissector ("invrtu", "invascii");
// call at protocol registration.
void register_transport_dissectors(InverterProtocol& protocol);

// Attaches the handles to TCP, UDP and RTAC serial; call at handoff.
void register_transport_handoffs(InverterProtocol& protocol);

}  // namespace pvtap::dissector
