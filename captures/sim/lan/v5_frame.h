// Solarman V5 frames as a logger stick and its LAN client write them: the frame's layout is
// the core's (pvtap/carriers/solarman_v5_frame.h); the payloads carry the simulated stick's
// clock.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "pvtap/carriers/solarman_v5_frame.h"

namespace pvtap::sim {

namespace v5_control = solarman_v5::control;

// V5Clock: the three u32 times of a stick's payload.
struct V5Clock {
  std::uint32_t total_working_s = 0;
  std::uint32_t power_on_s = 0;
  std::uint32_t offset_s = 0;  // power_on_s + offset_s is the Unix time
};

// The whole frame around `payload`, its checksum right; seq0 and seq1 are the sequence's two
// bytes as sent (a stick's reply echoes the client's seq0).
std::vector<std::uint8_t> v5_frame(std::uint16_t control, std::uint8_t seq0, std::uint8_t seq1,
                                   std::uint32_t serial, std::span<const std::uint8_t> payload);

// Response payload: frame type 0x02, status 0x01, the stick's times, RTU, `quirk` zero bytes.
std::vector<std::uint8_t> v5_response_payload(std::span<const std::uint8_t> rtu,
                                              const V5Clock& clock, std::size_t quirk);
// The answer to a stick's heartbeat or data report: its frame type, status 0x01, Unix time, 0.
std::vector<std::uint8_t> v5_answer_payload(std::uint8_t frame_type, std::uint32_t unix_s);

}  // namespace pvtap::sim
