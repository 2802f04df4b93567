// Tag numbers of Wireshark's exported-PDU link type 252 (wsutil/exported_pdu_tlvs.h) that
// pvtap reads and writes. Each tag is 2 bytes type, 2 bytes length, both big-endian, then
// the value; the list ends with the end tag of length 0.
#pragma once

#include <cstdint>
#include <string_view>

namespace pvtap::exported_pdu {

inline constexpr std::uint16_t kTagEnd = 0;
inline constexpr std::uint16_t kTagDissectorName = 12;
inline constexpr std::uint16_t kTagP2pDirection = 35;  // 4-byte signed value

// Wireshark's packet directions (epan/packet_info.h): the master's requests are "sent".
inline constexpr std::int32_t kDirectionSent = 0;
inline constexpr std::int32_t kDirectionReceived = 1;

// The dissector of pvtap's Wireshark plugin: the analyzer writes it into every record, the
// plugin registers under it.
inline constexpr char kDissectorName[] = "pvtap";

}  // namespace pvtap::exported_pdu
