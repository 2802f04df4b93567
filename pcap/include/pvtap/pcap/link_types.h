// The capture link types pvtap audit reads, and what kind of input each one is.
#pragma once

#include <optional>
#include <string>

namespace pvtap {

// Link type numbers as libpcap's pcap_datalink() reports them on Linux (DLT_*).
namespace dlt {
inline constexpr int kNull = 0;  // BSD loopback: 4-byte address family in host order
inline constexpr int kEthernet = 1;
inline constexpr int kRaw = 12;    // raw IP (LINKTYPE_RAW 101 in files)
inline constexpr int kLoop = 108;  // OpenBSD loopback: address family in network order
inline constexpr int kLinuxSll = 113;
inline constexpr int kUser0 = 147;
inline constexpr int kUser15 = 162;
inline constexpr int kIpv4 = 228;
inline constexpr int kIpv6 = 229;
inline constexpr int kRtacSerial = 250;
inline constexpr int kUpperPdu = 252;  // LINKTYPE_WIRESHARK_UPPER_PDU: exported PDUs
inline constexpr int kLinuxSll2 = 276;
}  // namespace dlt

// InputKind: how the records of a capture carry bus bytes.
enum class InputKind {
  Network,      // IP packets: TCP/UDP traffic of a serial-to-TCP gateway
  Serial,       // raw bus bytes in chunks (USER0-15)
  RtacSerial,   // raw bus bytes after a 12-byte RTAC header
  ExportedPdu,  // one frame per record, as pvtap audit --write produces
};

std::optional<InputKind> input_kind_of(int link_type);

// libpcap's name for a link type, for reports: "EN10MB (Ethernet)", "USER0".
std::string link_type_name(int link_type);

// "Ethernet (1), Linux cooked SLL (113), ..." for error messages and --help.
std::string supported_link_types_text();

}  // namespace pvtap
