// Recognizes RTU-shaped frames whose function code no dialect of the reference defines.
#pragma once

#include <cstdint>
#include <optional>
#include <span>

namespace pvtap {

// UnknownFunctionFrame: the header of such a frame.
struct UnknownFunctionFrame {
  std::uint8_t station = 0;
  std::uint8_t function = 0;
};

// Bytes that the framing rules left as noise, read as one whole RTU frame: a station 1..247,
// a function code that neither RTU dialect defines, and a good CRC-16/MODBUS over all of them.
// Such a run is most likely a frame of a function the reference does not describe (for
// example Modbus 0x01 read coils), not line noise.
std::optional<UnknownFunctionFrame> unknown_function_frame(std::span<const std::uint8_t> bytes);

}  // namespace pvtap
