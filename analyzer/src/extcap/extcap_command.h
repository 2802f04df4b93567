// Wireshark's extcap contract: pvtap lists the serial ports as capture interfaces and, when
// Wireshark starts a capture, sniffs the port into Wireshark's fifo as link type 252.
#pragma once

namespace pvtap::analyzer {

// True when Wireshark called the program as an extcap (--extcap-interfaces, --capture, ...).
bool is_extcap_call(int argc, char** argv);

// Answers one extcap call; returns the exit status.
int run_extcap(int argc, char** argv);

}  // namespace pvtap::analyzer
