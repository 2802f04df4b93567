// The ASCII dialect's frame layout: ENQ/ACK, hex fields, 'R', checksum, EOT (private).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "codec/wire_fields.h"
#include "pvtap/codec/frame_codec.h"

namespace pvtap::detail {

inline constexpr std::uint8_t kEnq = 0x05;
inline constexpr std::uint8_t kAck = 0x06;
inline constexpr std::uint8_t kEot = 0x04;
inline constexpr std::size_t kAsciiRequestLength = 15;
inline constexpr std::size_t kAsciiReplyOverhead = 13;  // + 4 per data word

// Fills `f` (see wire_fields.h).
ParseStatus parse_ascii(std::span<const std::uint8_t> bytes, Role role, Frame& f);
FrameCheck verify_ascii_check(std::span<const std::uint8_t> bytes);
bool encode_ascii(const Frame& frame, std::vector<std::uint8_t>& out);

}  // namespace pvtap::detail
