#include "pvtap/codec/checksums.h"

#include <array>

namespace pvtap {
namespace {

// Eight tables let the CRC consume eight bytes per step (slicing-by-8): the reassembler
// checks every frame, so the CRC is most of its cost on a clean stream.
using CrcTables = std::array<std::array<std::uint16_t, 256>, 8>;

constexpr CrcTables make_crc_tables() {
  CrcTables t{};
  for (unsigned i = 0; i < 256; ++i) {
    auto crc = static_cast<std::uint16_t>(i);
    for (int bit = 0; bit < 8; ++bit) {
      crc = static_cast<std::uint16_t>((crc & 1u) ? (crc >> 1) ^ 0xA001u : crc >> 1);
    }
    t[0][i] = crc;
  }
  for (unsigned i = 0; i < 256; ++i) {
    for (std::size_t k = 1; k < 8; ++k) {
      const std::uint16_t prev = t[k - 1][i];
      t[k][i] = static_cast<std::uint16_t>((prev >> 8) ^ t[0][prev & 0xFFu]);
    }
  }
  return t;
}

constexpr CrcTables kCrcTables = make_crc_tables();

}  // namespace

std::uint16_t Crc16Modbus::update(std::uint16_t crc, std::span<const std::uint8_t> bytes) {
  const std::uint8_t* p = bytes.data();
  std::size_t n = bytes.size();
  const auto& t = kCrcTables;
  while (n >= 8) {
    const unsigned a = (p[0] ^ crc) & 0xFFu;
    const unsigned b = (p[1] ^ (crc >> 8)) & 0xFFu;
    crc = static_cast<std::uint16_t>(t[7][a] ^ t[6][b] ^ t[5][p[2]] ^ t[4][p[3]] ^ t[3][p[4]] ^
                                     t[2][p[5]] ^ t[1][p[6]] ^ t[0][p[7]]);
    p += 8;
    n -= 8;
  }
  // Frames are short, so most of their bytes fall here: take 4 and 2 at a time as well.
  if (n >= 4) {
    const unsigned a = (p[0] ^ crc) & 0xFFu;
    const unsigned b = (p[1] ^ (crc >> 8)) & 0xFFu;
    crc = static_cast<std::uint16_t>(t[3][a] ^ t[2][b] ^ t[1][p[2]] ^ t[0][p[3]]);
    p += 4;
    n -= 4;
  }
  if (n >= 2) {
    const unsigned a = (p[0] ^ crc) & 0xFFu;
    const unsigned b = (p[1] ^ (crc >> 8)) & 0xFFu;
    crc = static_cast<std::uint16_t>(t[1][a] ^ t[0][b]);
    p += 2;
    n -= 2;
  }
  if (n == 1) crc = static_cast<std::uint16_t>((crc >> 8) ^ t[0][(crc ^ *p) & 0xFFu]);
  return crc;
}

std::uint16_t Crc16Modbus::compute(std::span<const std::uint8_t> bytes) {
  return update(kInit, bytes);
}

std::uint16_t AsciiChecksum::compute(std::span<const std::uint8_t> bytes) {
  unsigned sum = 0;
  for (auto b : bytes) sum += b;
  return static_cast<std::uint16_t>(sum & 0xFFFFu);
}

}  // namespace pvtap
