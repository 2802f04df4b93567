// The simulator's capture files: one function per carrier, each returning an error text
// (empty on success).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "bus/bus_event.h"

namespace pvtap::sim {

// Link type 252: one exported-PDU record per frame or noise run, tagged with its direction.
std::string write_pdu_capture(const BusTimeline& timeline, const std::string& path);

// ChunkedReads: how late the capturing program reads what the adapter hands over.
struct ChunkedReads {
  std::uint64_t seed = 0;
  unsigned max_delay_ms = 0;  // 0: every transfer read, and stamped, the moment it arrives
};

// USER0 (147): the bus bytes in chunks cut by a USB adapter's latency timer, as a serial
// sniffer records them; no direction. `pair`: only the bytes that side drove (one pair of a
// 4-wire bus: the master's requests, or the slaves' replies and the noise), through an adapter
// of its own.
std::string write_chunked_capture(const BusTimeline& timeline, const std::string& path,
                                  const ChunkedReads& reads,
                                  std::optional<Role> pair = std::nullopt);

// Ethernet/IPv4/TCP: the master's connection to a serial-to-TCP gateway, the gateway's
// stream cut into segments at random points.
std::string write_gateway_capture(const BusTimeline& timeline, const std::string& path,
                                  std::uint64_t seed);

}  // namespace pvtap::sim
