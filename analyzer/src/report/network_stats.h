// NetworkStats: what happened to a capture's TCP and UDP flows, counted by the gateway layer
// and shown by the report.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "pvtap/carriers/solarman_v5_reader.h"

namespace pvtap::analyzer {

struct NetworkStats {
  std::uint64_t flows_analyzed = 0;
  std::uint64_t flows_ignored = 0;  // no inverter frames, or not on --port
  std::uint64_t ignored_bytes = 0;  // payload of ignored flows
  std::uint64_t retransmitted_bytes = 0;
  std::uint64_t out_of_order_segments = 0;
  std::uint64_t lost_bytes = 0;
  std::uint64_t gaps = 0;
  // Modbus/TCP flows: their ADUs, the MBAP header bytes (the carrier's, never noise), and
  // the headers that lied with the bytes given up for them.
  std::uint64_t mbap_flows = 0;
  std::uint64_t mbap_adus = 0;
  std::uint64_t mbap_carrier_bytes = 0;
  std::uint64_t mbap_findings = 0;
  std::uint64_t mbap_skipped_bytes = 0;
  static constexpr std::size_t kMaxExamples = 5;
  std::vector<std::string> mbap_finding_examples;  // "bus: what the header said", the first few
  std::uint64_t v5_flows = 0;  // of the analyzed flows, those to Solarman V5 logger sticks
  solarman_v5::Totals v5;      // what their V5 frames carried, and their findings
  // The sticks' codes said plainly (SolarmanV5Flow::finding_examples), the first few.
  std::vector<std::string> v5_finding_examples;
};

}  // namespace pvtap::analyzer
