// Coils and discrete inputs as addressed bits: read replies, single and multiple writes.
#pragma once

#include <cstdint>
#include <optional>
#include <span>

#include "pvtap/codec/frame.h"
#include "pvtap/registers/register_map.h"

namespace pvtap {

// CoilBits: a run of addressed bits of one frame. Bit i is coil (or input) `start + i`;
// bit 0 of byte 0 is the first (the packing of the specification).
struct CoilBits {
  std::optional<std::uint16_t> start;  // unknown for a read reply without its request
  std::uint16_t count = 0;             // the bits that are coils: a read's quantity
  std::span<const std::uint8_t> bytes;
  bool inputs = false;  // discrete inputs (0x02) rather than coils

  bool on(std::size_t i) const { return ((unsigned{bytes[i / 8]} >> (i % 8)) & 1u) != 0; }
  // The address of bit i, when the start is known and the address within 0 .. 65535.
  std::optional<std::uint16_t> address(std::size_t i) const;
};

// The bits a frame carries, or nullopt for a frame that carries none:
//   0x01 0x02 reply    the request's start and quantity (without it: 8 bits per byte)
//   0x05 request/echo  one coil: on for 0xFF00, off for 0x0000 (nullopt for other values)
//   0x0F request       start, quantity and its bytes
// A quantity the bytes cannot hold is cut to what they hold.
std::optional<CoilBits> coil_bits(const Frame& frame, const Frame* request);

// What a map says of bit i: its [[coil]] or [[discrete_input]] entry (as the bits are), or
// null when the map does not name that address or the bits' start is unknown.
const CoilDef* coil_def(const RegisterMap& map, const CoilBits& bits, std::size_t i);

}  // namespace pvtap
