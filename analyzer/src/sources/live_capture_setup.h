// LiveCaptureSetup: a libpcap capture on an interface made ready to read, and what that
// settled: the link type, the timestamp precision, the filter in force, libpcap's warnings.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "pvtap/pcap/capture_file.h"

namespace pvtap::analyzer {

// LiveCaptureSettings: which interface, and which of its traffic (gateway ports, BPF filter).
struct LiveCaptureSettings {
  std::string interface;
  std::vector<std::uint16_t> ports;  // each is matched as TCP and UDP, either side
  std::string filter;                // the user's BPF filter, AND-ed with the ports
};

// The BPF filter for `ports` and a user filter: "(tcp port 1 or udp port 1 ...) and (user)";
// empty when there is neither.
std::string live_capture_filter(const std::vector<std::uint16_t>& ports,
                                const std::string& user_filter);

// PcapHandle: a capture, closed with its owner.
struct PcapClose {
  void operator()(pcap_t* pcap) const;
};
using PcapHandle = std::unique_ptr<pcap_t, PcapClose>;

struct LiveCaptureSetup {
  int link_type = -1;
  bool nanoseconds = false;            // timestamps in nanoseconds, else microseconds
  std::string filter;                  // as applied; empty for none
  std::vector<std::string> warnings;   // libpcap's when it activated the capture, each a line
  std::string link_type_name() const;  // "EN10MB (Ethernet)"
};

// Creates and activates the capture into `pcap`, checks its link type and sets its filter;
// false with `error` set to a one-line reason (a missing capability, an unknown interface, a
// bad filter). `pcap` holds what was created even then.
bool set_up_live_capture(const LiveCaptureSettings& settings, PcapHandle& pcap,
                         LiveCaptureSetup& setup, std::string& error);

}  // namespace pvtap::analyzer
