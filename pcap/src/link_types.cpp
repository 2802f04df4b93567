#include "pvtap/pcap/link_types.h"

#include <pcap/pcap.h>

namespace pvtap {

std::optional<InputKind> input_kind_of(int link_type) {
  switch (link_type) {
    case dlt::kNull:
    case dlt::kEthernet:
    case dlt::kRaw:
    case dlt::kLoop:
    case dlt::kLinuxSll:
    case dlt::kLinuxSll2:
    case dlt::kIpv4:
    case dlt::kIpv6:
      return InputKind::Network;
    case dlt::kRtacSerial:
      return InputKind::RtacSerial;
    case dlt::kUpperPdu:
      return InputKind::ExportedPdu;
    default:
      break;
  }
  if (link_type >= dlt::kUser0 && link_type <= dlt::kUser15) return InputKind::Serial;
  return std::nullopt;
}

std::string link_type_name(int link_type) {
  if (link_type >= DLT_USER0 && link_type <= DLT_USER15) {
    return "USER" + std::to_string(link_type - DLT_USER0);
  }
  const char* name = pcap_datalink_val_to_name(link_type);
  const char* description = pcap_datalink_val_to_description(link_type);
  std::string out = name != nullptr ? name : "link type " + std::to_string(link_type);
  if (description != nullptr) out += std::string(" (") + description + ")";
  return out;
}

std::string supported_link_types_text() {
  return "Ethernet (1), Linux cooked SLL (113) and SLL2 (276), raw IP (101, 228, 229), "
         "loopback (0, 108), USER0-USER15 (147-162), RTAC serial (250), "
         "exported PDU (252)";
}

}  // namespace pvtap
