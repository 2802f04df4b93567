// Noise resemblance: whether a run of noise looks like a damaged frame of the ASCII dialect.
#pragma once

#include <cstdint>
#include <span>

namespace pvtap {

// True when the run starts as an ASCII frame does (ENQ or ACK) and most of the rest is what
// such a frame carries (printable characters, EOT): a damaged ASCII frame rather than RTU
// bytes or line noise, so that it is filed with the ASCII dialect. A damaged byte or two may be
// anything, so three quarters of the rest suffice.
bool resembles_ascii_frame(std::span<const std::uint8_t> bytes);

}  // namespace pvtap
