// LiveOptions: what a live capture reads and when it stops, as pvtap sniff and the extcap set it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "serial/serial_line.h"

namespace pvtap::analyzer {

struct LiveOptions {
  std::vector<std::string> devices;  // serial devices (RS485 taps), each its own bus
  // --duplex: the two devices are the two pairs of one 4-wire bus, the requests' first.
  bool duplex = false;
  SerialLine line;
  bool search_line = false;  // --baud auto: each tap's rate and format are searched, not given
  // --logic: a logic analyzer's binary samples ("-": standard input), their rate, and the
  // names of their bits from bit 0 on.
  std::string logic_input;
  double sample_rate = 0;
  std::vector<std::string> logic_channels;
  std::string interface;     // a network interface with a gateway's TCP traffic (libpcap)
  std::string filter;        // BPF filter for the interface, added to the --port filter
  double duration = 0;       // seconds; 0 runs until SIGINT/SIGTERM
  std::uint64_t count = 0;   // frames; 0 means no limit
  bool status_line = false;  // a live status line on stderr
  bool quiet = false;        // nothing on stdout (extcap: the frames go to the fifo)
};

}  // namespace pvtap::analyzer
