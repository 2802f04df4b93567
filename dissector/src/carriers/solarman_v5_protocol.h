// SolarmanV5Protocol: invv5, the logger stick's V5 frames on TCP around invrtu's frames.
#pragma once

#include <epan/expert.h>
#include <epan/packet.h>

#include <array>
#include <cstddef>
#include <cstdint>

namespace pvtap::dissector {

// invv5's fields, one line each: X(id, name, abbrev, type, display, value names, blurb), with
// abbrevs relative to "invv5" and value names an expression of solarman_v5_protocol.cpp.
// Registered in this order, which is the order `tshark -G fields` lists them in.
#define PVTAP_V5_FIELDS(X)                                                                      \
  X(Length, "Payload length", "length", FT_UINT16, BASE_DEC, nullptr, nullptr)                  \
  X(Control, "Control code", "control", FT_UINT16, BASE_HEX, kControlNames, nullptr)            \
  X(Sequence, "Sequence", "sequence", FT_UINT16, BASE_HEX, nullptr,                             \
    "Low byte set by the client and echoed; high byte counted by the stick")                    \
  X(Serial, "Logger serial", "serial", FT_UINT32, BASE_DEC, nullptr,                            \
    "Serial number of the logger stick")                                                        \
  X(FrameType, "Frame type", "frame_type", FT_UINT8, BASE_HEX, nullptr, nullptr)                \
  X(SensorType, "Sensor type", "sensor_type", FT_UINT16, BASE_HEX, nullptr, nullptr)            \
  X(Status, "Status", "status", FT_UINT8, BASE_HEX, nullptr, nullptr)                           \
  X(TotalWorkingTime, "Total working time", "total_working_time", FT_UINT32, BASE_DEC, nullptr, \
    nullptr)                                                                                    \
  X(PowerOnTime, "Power-on time", "power_on_time", FT_UINT32, BASE_DEC, nullptr, nullptr)       \
  X(OffsetTime, "Offset time", "offset_time", FT_UINT32, BASE_DEC, nullptr, nullptr)            \
  /* a stick frame's payload, or one too short for its fixed fields */                          \
  X(Payload, "Payload", "payload", FT_BYTES, BASE_NONE, nullptr, nullptr)                       \
  X(Rtu, "Modbus RTU frame", "rtu", FT_BYTES, BASE_NONE, nullptr,                               \
    "The RTU frame the stick carries, dissected by invrtu")                                     \
  X(Quirk, "Extra bytes after the RTU CRC", "quirk", FT_BYTES, BASE_NONE, nullptr,              \
    "Two zero bytes some sticks append to a response")                                          \
  X(Checksum, "Checksum", "checksum", FT_UINT8, BASE_HEX, nullptr,                              \
    "Sum of the bytes from the length to the payload's end, mod 256")                           \
  X(ChecksumStatus, "Checksum status", "checksum.status", FT_UINT8, BASE_NONE,                  \
    proto_checksum_vals, nullptr)                                                               \
  X(Broken, "Broken V5 frame", "broken", FT_BYTES, BASE_NONE, nullptr,                          \
    "Bytes that start like a V5 frame but are none: truncated, or their length does not hold")  \
  X(ClaimedLength, "Claimed frame size", "claimed_size", FT_UINT32, BASE_DEC, nullptr,          \
    "The size the broken frame's length field claims")                                          \
  X(Noise, "Not V5", "noise", FT_BYTES, BASE_NONE, nullptr,                                     \
    "Bytes of the flow that are no V5 frame")                                                   \
  X(StickCode, "Stick code", "stick_code", FT_UINT8, BASE_HEX, nullptr,                         \
    "The stick's own code in place of an RTU frame (05: no reply from the bus; 06: the "        \
    "request named another logger serial)")

// invv5's expert infos: X(id, abbrev, group, severity, summary).
#define PVTAP_V5_EXPERTS(X)                                                               \
  X(BadChecksum, "checksum.bad", PI_CHECKSUM, PI_ERROR, "Bad V5 checksum")                \
  X(Truncated, "truncated", PI_MALFORMED, PI_ERROR, "Truncated V5 frame")                 \
  X(LengthMismatch, "length_mismatch", PI_MALFORMED, PI_ERROR, "V5 length does not hold") \
  X(PayloadShort, "payload_short", PI_MALFORMED, PI_ERROR,                                \
    "V5 payload shorter than its fixed fields")                                           \
  X(Quirk, "quirk_found", PI_PROTOCOL, PI_NOTE,                                           \
    "Two zero bytes after the RTU CRC (a known stick quirk)")                             \
  X(Noise, "not_v5", PI_UNDECODED, PI_WARN, "Bytes that are no V5 frame")                 \
  X(StickNoReply, "stick_no_reply", PI_RESPONSE_CODE, PI_WARN,                            \
    "The stick answered code 05: no reply from the bus behind it (a timeout)")            \
  X(StickRefused, "stick_refused", PI_RESPONSE_CODE, PI_WARN,                             \
    "The stick refused a request addressed to another logger serial (code 06)")           \
  X(StickCode, "stick_code_other", PI_RESPONSE_CODE, PI_NOTE,                             \
    "The stick answered a code in place of an RTU frame")

// V5Field, V5Expert: invv5's fields and expert infos, by line of the tables above.
#define PVTAP_V5_ID(id, ...) id,
enum class V5Field : std::uint8_t { PVTAP_V5_FIELDS(PVTAP_V5_ID) };
enum class V5Expert : std::uint8_t { PVTAP_V5_EXPERTS(PVTAP_V5_ID) };
#undef PVTAP_V5_ID
#define PVTAP_V5_ONE(...) +1
inline constexpr std::size_t kV5FieldCount = 0 PVTAP_V5_FIELDS(PVTAP_V5_ONE);
inline constexpr std::size_t kV5ExpertCount = 0 PVTAP_V5_EXPERTS(PVTAP_V5_ONE);
#undef PVTAP_V5_ONE

// SolarmanV5Protocol: invv5 and the ids Wireshark assigned it (-1 until registered).
struct SolarmanV5Protocol {
  int proto = -1;
  std::array<int, kV5FieldCount> hf = [] {
    std::array<int, kV5FieldCount> ids{};
    ids.fill(-1);
    return ids;
  }();
  std::array<expert_field, kV5ExpertCount> ei = [] {
    std::array<expert_field, kV5ExpertCount> ids{};
    ids.fill(expert_field EI_INIT);
    return ids;
  }();
  int ett_frame = -1;
  dissector_handle_t handle = nullptr;

  int field(V5Field f) const { return hf[static_cast<std::size_t>(f)]; }
  expert_field* expert(V5Expert e) { return &ei[static_cast<std::size_t>(e)]; }
};

SolarmanV5Protocol& v5_protocol();
// The name of a control code, for the tree and the Info column.
const char* v5_control_name(std::uint16_t control);

// Registers invv5 (its fields, expert infos, subtree and handle); call at registration.
void register_v5_protocol();
// Attaches invv5 to TCP: a heuristic, and a port preference (empty) for Decode As.
void register_v5_handoff();

}  // namespace pvtap::dissector
