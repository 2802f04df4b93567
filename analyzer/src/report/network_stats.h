// NetworkStats: what happened to a capture's TCP and UDP flows, counted by the gateway layer
// and shown by the report.
#pragma once

#include <cstdint>

namespace pvtap::analyzer {

struct NetworkStats {
  std::uint64_t flows_analyzed = 0;
  std::uint64_t flows_ignored = 0;  // no inverter frames, or not on --port
  std::uint64_t ignored_bytes = 0;  // payload of ignored flows
  std::uint64_t retransmitted_bytes = 0;
  std::uint64_t out_of_order_segments = 0;
  std::uint64_t lost_bytes = 0;
  std::uint64_t gaps = 0;
};

}  // namespace pvtap::analyzer
