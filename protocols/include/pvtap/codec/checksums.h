// The two integrity checks: CRC-16/MODBUS (RTU dialects) and the ASCII additive sum.
#pragma once

#include <cstdint>
#include <span>

namespace pvtap {

// Crc16Modbus: CRC-16/MODBUS (poly 0xA001 reflected, init 0xFFFF), table driven.
// On the wire it is sent low byte first.
struct Crc16Modbus {
  static std::uint16_t compute(std::span<const std::uint8_t> bytes);
  static constexpr std::uint16_t kInit = 0xFFFF;
  static std::uint16_t update(std::uint16_t crc, std::span<const std::uint8_t> bytes);
};

// AsciiChecksum: the ASCII dialect's plain 16-bit sum of byte values.
struct AsciiChecksum {
  static std::uint16_t compute(std::span<const std::uint8_t> bytes);
};

}  // namespace pvtap
