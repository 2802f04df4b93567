// The LAN side of a Modbus/TCP gateway: a client sends each request as an MBAP ADU
// (transaction id, protocol 0, length, unit id = station, PDU) to port 502, sometimes the next
// one before the last reply (pipelined); the gateway queues them onto the bus and answers
// exception 0x0B where the bus device stayed silent.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "lan/carrier_faults.h"
#include "lan/lan_capture.h"

namespace pvtap::sim {

// The fault kinds of --mbap-faults.
const std::vector<std::string>& mbap_fault_kinds();

struct MbapOptions {
  // pipeline: a request sent before the reply to the one before it; lying_length: a reply
  // whose MBAP length field says 1-3 bytes more than it carries.
  CarrierFaults faults;
  double bus_timeout_s = 1.0;  // the gateway's wait for the bus, the master's timeout
};

LanCapture plan_mbap_session(const BusTimeline& timeline, const MbapOptions& options,
                             std::uint64_t seed);

}  // namespace pvtap::sim
