// One TCP connection from a LAN client to a device, planned as segments and written as an
// Ethernet capture with its handshake, sequence and acknowledgement numbers and FIN.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "bus/bus_event.h"

namespace pvtap::sim {

// LanSegment: one TCP segment before sequence numbers are known.
struct LanSegment {
  Micros time = 0;
  bool from_client = false;
  std::vector<std::uint8_t> payload;  // empty: a bare ACK
};

// The two ends: the client (Home Assistant, a SCADA poller) and the device's listening port.
struct LanEndpoints {
  std::uint16_t client_port = 0;
  std::uint16_t device_port = 0;
};

// Writes the segments in time order, opening the connection 50 ms before the first and
// closing it 100 ms after the last; an error text, empty on success.
std::string write_tcp_session(std::vector<LanSegment> segments, const LanEndpoints& ends,
                              const std::string& path);

}  // namespace pvtap::sim
