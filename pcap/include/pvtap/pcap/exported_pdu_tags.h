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

// pvtap's own tags, outside the numbers Wireshark gives out (it shows them as unknown tags and
// still hands the record to the dissector named): what the run that wrote a record knew of it,
// so that reading the file again gives that run's verdicts (dissector/README.md).
// kTagPvtapRecord: version 1, kind (1 frame, 2 noise, 3 the end of the run: no bytes, its
// time the last the run's clock read, which judged the requests still waiting; 4 capture data
// lost: no bytes), the direction of the stream it was read from (0 one stream for both, a tap;
// 1 master to slave; 2 slave to master), a zero byte, then the start of its first byte and the
// end of its last, IEEE 754 doubles of Unix seconds; a loss whose size is known adds the count
// of bytes lost (64 bits).
inline constexpr std::uint16_t kTagPvtapRecord = 0x7076;
inline constexpr std::uint16_t kPvtapRecordLength = 20;
inline constexpr std::uint16_t kPvtapLossRecordLength = 28;
// kTagPvtapRun: version 1, the dialects read (bit per dialect: 1 ASCII, 2 Hybrid, 4 GSL,
// 8 Modbus; 0x80 GSL/Modbus ties go to Modbus), two zero bytes, the baud rate (32 bits), the
// reply timeout in seconds (a double), then the bus's name (UTF-8, the rest of the value).
inline constexpr std::uint16_t kTagPvtapRun = 0x7077;
inline constexpr std::uint16_t kPvtapRunFixedLength = 16;
inline constexpr std::uint8_t kPvtapTagVersion = 1;

// Wireshark's packet directions (epan/packet_info.h): the master's requests are "sent".
inline constexpr std::int32_t kDirectionSent = 0;
inline constexpr std::int32_t kDirectionReceived = 1;

// The dissector of pvtap's Wireshark plugin: the analyzer writes it into every record of bus
// bytes, the plugin registers under it.
inline constexpr char kDissectorName[] = "pvtap";
// Records that mark a moment rather than carry bus bytes (the end of the run, capture data
// lost) name this dissector and carry one line of text saying what they mark: Wireshark hands
// a record without bytes to no dissector (it shows "<MISSING>"), and a bus dissector must
// never take the text for bytes of the bus.
inline constexpr char kEventDissectorName[] = "pvtap.event";

}  // namespace pvtap::exported_pdu
