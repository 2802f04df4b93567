// The protocol a capture record shows as: the one of the frame it starts with.
#pragma once

#include <epan/packet.h>

#include "protocol/inverter_protocol.h"
#include "pvtap/framing/framing_probe.h"

namespace pvtap::dissector {

// The protocol of the complete frame that starts the record (invrtu when none does); the
// record's pieces still go to the protocols of their own dialects.
InverterProtocol& protocol_of_record(tvbuff_t* tvb, packet_info* pinfo, RoleHint hint);

}  // namespace pvtap::dissector
