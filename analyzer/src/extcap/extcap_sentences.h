// The answers pvtap gives to Wireshark's extcap questions, in the contract's sentence format
// (`interface {value=...}{display=...}`, see extcap(4)).
#pragma once

#include <string>
#include <vector>

#include "extcap/extcap_port_discovery.h"

namespace pvtap::analyzer {

// --extcap-interfaces: the program line, then one interface per serial port.
std::string interfaces_answer(const std::vector<DiscoveredPort>& ports);

// --extcap-dlts: link type 252, Wireshark's exported PDUs, read by pvtap's plugin.
std::string dlts_answer();

// --extcap-config: baud rate, parity, stop bits and dialect with their choices and defaults;
// then, for `interface`, the 4-wire selector of the other ports' taps (the replies' pair).
std::string config_answer(const std::vector<DiscoveredPort>& ports, const std::string& interface);

// The --duplex-replies value of a 2-wire bus.
inline constexpr const char* kNoDuplex = "none";

}  // namespace pvtap::analyzer
