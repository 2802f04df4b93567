// The LAN side of a Solarman V5 logger stick: a client (Home Assistant, say) sends each RTU
// request in a V5 frame to the stick on TCP 8899, the stick puts it on the bus and wraps the
// reply; the stick's own heartbeats and data reports, which the client answers, and the faults
// of real sticks besides.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "lan/carrier_faults.h"
#include "lan/lan_capture.h"

namespace pvtap::sim {

// The fault kinds of --v5-faults.
const std::vector<std::string>& v5_fault_kinds();

struct V5Options {
  // quirk: two 0x00 bytes after a reply's RTU CRC; drop: the stick sends no reply (the
  // request is a timeout); bad_checksum: a reply's V5 checksum off; split: a reply in two TCP
  // segments; merge: a heartbeat and a reply in one segment; stick_code: the stick answers a
  // request the bus left unanswered with code 05 in place of an RTU frame; wrong_serial: the
  // client addresses another logger serial, the stick refuses with code 06 and its own serial
  // (the request never reaches the bus); late: the reply comes after the client's next
  // request; beat_first: a heartbeat where the reply was due, the reply late.
  CarrierFaults faults;
  double heartbeat_s = 0;    // 0: none
  double data_report_s = 0;  // 0: none
  std::uint32_t logger_serial = 2712345678u;
  std::uint32_t wrong_serial = 2111130827u;  // what a client with the wrong serial addresses
  // The client's wait for a reply (--timeout): late replies and codes 05 come within it.
  double client_timeout_s = 1.0;
};

// Plans the V5 capture of `timeline` and makes the timeline what the client saw (replies the
// stick dropped removed, their requests timeouts); `start` is the run's start.
LanCapture plan_v5_session(BusTimeline& timeline, const V5Options& options, Micros start,
                           std::uint64_t seed);

}  // namespace pvtap::sim
