// Solarman V5: the frame a Wi-Fi/LAN logger stick wraps around each Modbus RTU frame.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace pvtap::solarman_v5 {

inline constexpr std::uint8_t kStart = 0xA5;
inline constexpr std::uint8_t kEnd = 0x15;
// start(1) length(2) control(2) sequence(2) logger serial(4)
inline constexpr std::size_t kHeaderSize = 11;
inline constexpr std::size_t kTrailerSize = 2;  // checksum(1) end(1)
inline constexpr std::size_t kOverhead = kHeaderSize + kTrailerSize;
// A bound on the payload length, so that a 0xA5 in other traffic cannot make a reader hold
// 64 KiB waiting for a frame: real payloads carry one RTU frame (at most 256 bytes) or a
// stick's data report of a few hundred bytes.
inline constexpr std::size_t kMaxPayload = 1024;
// Fixed fields before the RTU frame: frame type(1) sensor type(2) three u32 times.
inline constexpr std::size_t kRequestFixed = 15;
// Fixed fields before the RTU frame: frame type(1) status(1) three u32 times.
inline constexpr std::size_t kResponseFixed = 14;
// Some sticks append two zero bytes after the RTU CRC of a response.
inline constexpr std::size_t kQuirkSize = 2;
// A response whose payload holds two bytes where the RTU frame belongs (no RTU frame is
// shorter than four) carries the stick's own code: the code, then 0.
inline constexpr std::size_t kStickCodeSize = 2;

// The stick codes whose meaning sticks and their client libraries agree on; others are
// reported as codes.
namespace stick_code {
inline constexpr std::uint8_t kNoReply = 0x05;      // no RTU reply came from the bus
inline constexpr std::uint8_t kWrongSerial = 0x06;  // the request named another logger serial
}  // namespace stick_code

// Control codes (little endian on the wire). A stick answers its own frames with the code
// less 0x3000.
namespace control {
inline constexpr std::uint16_t kRequest = 0x4510;
inline constexpr std::uint16_t kResponse = 0x1510;
inline constexpr std::uint16_t kHandshake = 0x4110;
inline constexpr std::uint16_t kDataReport = 0x4210;
inline constexpr std::uint16_t kWifiInfo = 0x4310;
inline constexpr std::uint16_t kHeartbeat = 0x4710;
inline constexpr std::uint16_t kReport = 0x4810;
inline constexpr std::uint16_t kReplyOffset = 0x3000;
}  // namespace control

// FrameKind: what a control code makes a frame.
enum class FrameKind : std::uint8_t {
  Request,     // a client's Modbus RTU request
  Response,    // the stick's Modbus RTU response
  StickFrame,  // the stick's own frames: handshake, data report, wifi info, heartbeat
  StickReply,  // the answer to one of them (its code less 0x3000)
  Other,       // a control code nothing documents
};
FrameKind kind_of(std::uint16_t control_code);
// A control code that a V5 frame is known to carry.
inline bool known_control(std::uint16_t code) {
  return kind_of(code) != FrameKind::Other;
}

// Header: the fields before the payload.
struct Header {
  std::uint16_t length = 0;  // of the payload
  std::uint16_t control = 0;
  std::uint16_t sequence = 0;
  std::uint32_t serial = 0;  // the logger stick's serial number
};

// Frame: one whole V5 frame (start to end byte) and what its payload carries. Spans point
// into the bytes it was parsed from.
struct Frame {
  Header header;
  FrameKind kind = FrameKind::Other;
  std::span<const std::uint8_t> bytes;  // the whole frame
  std::uint8_t checksum = 0;            // as sent
  std::uint8_t expected_checksum = 0;
  bool checksum_ok() const { return checksum == expected_checksum; }
  // Request and response payloads: their fixed fields.
  std::uint8_t frame_type = 0;
  std::uint16_t sensor_type = 0;  // requests
  std::uint8_t status = 0;        // responses
  std::uint32_t total_working_time = 0;
  std::uint32_t power_on_time = 0;
  std::uint32_t offset_time = 0;
  // A request or response payload shorter than its fixed fields: its length does not hold.
  bool payload_short = false;
  std::size_t rtu_offset = 0;  // in bytes
  std::size_t rtu_length = 0;
  std::size_t quirk_bytes = 0;  // the two zeros after the RTU CRC (0 or kQuirkSize)
  // A response carrying the stick's code in place of an RTU frame (at rtu_offset; rtu_length
  // is then 0, and the code's two bytes are the carrier's).
  std::optional<std::uint8_t> stick_code;
  std::span<const std::uint8_t> rtu() const { return bytes.subspan(rtu_offset, rtu_length); }
  // Bytes that belong to the carrier: everything but the RTU frame and the quirk.
  std::size_t carrier_bytes() const { return bytes.size() - rtu_length - quirk_bytes; }
};

// The checksum of a frame: the sum of its bytes from the length to the payload's end, mod 256.
std::uint8_t checksum_of(std::span<const std::uint8_t> frame_bytes);
// The header of the bytes at a frame start (at least kHeaderSize of them).
Header read_header(std::span<const std::uint8_t> bytes);
// Parses a whole frame: exactly kOverhead + its length bytes, start and end bytes in place.
Frame parse_frame(std::span<const std::uint8_t> bytes);

// The wire encoding of a frame with a correct checksum around `payload`.
std::vector<std::uint8_t> encode_frame(const Header& header, std::span<const std::uint8_t> payload);
// A request payload around `rtu` (frame type 2: the inverter), times zero, as clients send.
std::vector<std::uint8_t> request_payload(std::span<const std::uint8_t> rtu);
// A response payload around `rtu`, with `quirk` zero bytes after it.
std::vector<std::uint8_t> response_payload(std::span<const std::uint8_t> rtu, bool quirk = false);

}  // namespace pvtap::solarman_v5
