// Service Response Time tables (tshark -z invrtu,srt / -z invascii,srt), a row per function.
#pragma once

#include <epan/packet.h>

#include "plan/frame_record.h"
#include "protocol/inverter_protocol.h"

namespace pvtap::dissector {

// Registers the protocol's tap and its SRT table; call at protocol registration.
void register_response_time_stats(InverterProtocol& protocol);

// Reports one answered request to the SRT tap (call for every reply shown).
void queue_response_time(packet_info* pinfo, const InverterProtocol& protocol,
                         const FrameRecord& reply);

}  // namespace pvtap::dissector
