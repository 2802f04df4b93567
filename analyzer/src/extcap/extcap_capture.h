// A --capture call of Wireshark's extcap contract: the chosen port sniffed into Wireshark's
// fifo as link type 252, until Wireshark stops the capture with SIGTERM.
#pragma once

#include <string>
#include <vector>

#include "cli/command_options.h"
#include "extcap/extcap_arguments.h"
#include "extcap/extcap_port_discovery.h"

namespace pvtap::analyzer {

// Why a capture filter is refused, for the filter check and for a capture given one anyway.
inline constexpr const char* kNoCaptureFilter =
    "RS485 taps take no capture filter; use a display filter (invrtu, invascii)";

// The live capture options of `pvtap sniff --device PORT --write FIFO` with the dialog's
// settings, quiet on stdout (the frames go to the fifo). `settings` must be valid
// (settings_problems() empty).
SniffOptions capture_options(const DiscoveredPort& port, const ExtcapSettings& settings,
                             const std::string& fifo);

// Runs the capture until SIGTERM, or until Wireshark's end of the fifo is gone (no SIGPIPE
// death: the capture stops and exits 0); returns the exit status (2, after a line on stderr
// that Wireshark shows, when the call cannot be served).
int run_extcap_capture(const ExtcapCall& call, const std::vector<DiscoveredPort>& ports);

}  // namespace pvtap::analyzer
