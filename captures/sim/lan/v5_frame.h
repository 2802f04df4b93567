// Solarman V5 frames as a logger stick and its LAN client write them (pysolarmanv5's protocol
// notes): start 0xA5, payload length (LE), control code (LE), sequence (2), logger serial
// (LE), payload, checksum (the sum of the bytes between start and checksum, mod 256), 0x15.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace pvtap::sim {

namespace v5_control {
inline constexpr std::uint16_t kRequest = 0x4510;  // client to stick: an RTU request
inline constexpr std::uint16_t kResponse = 0x1510;
inline constexpr std::uint16_t kDataReport = 0x4210;  // the stick's own frames, each answered
inline constexpr std::uint16_t kDataAnswer = 0x1210;  // by the other side's 0x1x10
inline constexpr std::uint16_t kHeartbeat = 0x4710;
inline constexpr std::uint16_t kHeartbeatAnswer = 0x1710;
}  // namespace v5_control

// V5Clock: the three u32 times of a stick's payload.
struct V5Clock {
  std::uint32_t total_working_s = 0;
  std::uint32_t power_on_s = 0;
  std::uint32_t offset_s = 0;  // power_on_s + offset_s is the Unix time
};

inline constexpr std::size_t kV5Overhead = 13;  // header 11, checksum, end

// The whole frame around `payload`, its checksum right.
std::vector<std::uint8_t> v5_frame(std::uint16_t control, std::uint8_t seq0, std::uint8_t seq1,
                                   std::uint32_t serial, std::span<const std::uint8_t> payload);

// Request payload: frame type 0x02, sensor type 0, three zero times (as clients send), RTU.
std::vector<std::uint8_t> v5_request_payload(std::span<const std::uint8_t> rtu);
// Response payload: frame type 0x02, status 0x01, the stick's times, RTU, `quirk` zero bytes.
std::vector<std::uint8_t> v5_response_payload(std::span<const std::uint8_t> rtu,
                                              const V5Clock& clock, std::size_t quirk);
// The answer to a stick's heartbeat or data report: its frame type, status 0x01, Unix time, 0.
std::vector<std::uint8_t> v5_answer_payload(std::uint8_t frame_type, std::uint32_t unix_s);

// The checksum byte a frame should carry.
std::uint8_t v5_checksum(std::span<const std::uint8_t> frame);

}  // namespace pvtap::sim
