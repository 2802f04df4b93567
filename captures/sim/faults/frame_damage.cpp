#include "faults/frame_damage.h"

#include <charconv>

#include "pvtap/codec/frame_codec.h"
#include "pvtap/codec/function_codes.h"
#include "pvtap/matching/request_rules.h"

namespace pvtap::sim {
namespace {

constexpr std::uint8_t kEot = 0x04, kEnq = 0x05, kAck = 0x06;

bool is_hex_digit(std::uint8_t b) {
  return (b >= '0' && b <= '9') || (b >= 'a' && b <= 'f') || (b >= 'A' && b <= 'F');
}

// ENQ/ACK (0), 'R' (3) and EOT (last) as they were, every other byte a hex digit.
bool ascii_frame_shaped(std::span<const std::uint8_t> original,
                        std::span<const std::uint8_t> damaged) {
  const std::size_t last = damaged.size() - 1;
  for (std::size_t i = 0; i <= last; ++i) {
    const bool delimiter = i == 0 || i == 3 || i == last;
    if (delimiter ? damaged[i] != original[i] : !is_hex_digit(damaged[i])) return false;
  }
  return true;
}

bool good_crc_prefix(std::span<const std::uint8_t> damaged) {
  for (std::size_t n = 4; n < damaged.size(); ++n)
    if (verify_check(damaged.first(n), Dialect::Gsl).ok) return true;
  return false;
}

// A plain Modbus frame's length follows from its function (and a request's quantity is
// bounded): damage to the function byte, or a request quantity the specification rules out,
// leaves a run that reads as a frame of another length or as noise as well as a damaged frame.
bool modbus_shape_kept(std::span<const std::uint8_t> original,
                       std::span<const std::uint8_t> damaged, bool request) {
  if (damaged[1] != original[1]) return false;
  // A byte count (a read's reply, a block write's request) gives the length too.
  const bool counted =
      request ? original[1] == fc::kWriteMultipleCoils || original[1] == fc::kGslWriteMultiple
              : max_quantity(original[1]).has_value() && original[1] <= 0x04;
  if (counted && damaged[request ? 6 : 2] != original[request ? 6 : 2]) return false;
  // A single coil is written with FF00 or 0000 and nothing else.
  if (original[1] == fc::kWriteSingleCoil) {
    const unsigned value = static_cast<unsigned>(damaged[4] << 8 | damaged[5]);
    if (value != 0xFF00 && value != 0x0000) return false;
  }
  const std::optional<unsigned> limit = max_quantity(original[1]);
  if (!request || !limit) return true;
  const unsigned quantity = static_cast<unsigned>(damaged[4] << 8 | damaged[5]);
  if (quantity < 1 || quantity > *limit) return false;
  // A block write's byte count is fixed by its quantity.
  if (original[1] == fc::kWriteMultipleCoils) return damaged[6] == (quantity + 7) / 8;
  if (original[1] == fc::kGslWriteMultiple) return damaged[6] == 2 * quantity;
  return true;
}

}  // namespace

std::optional<DamageReading> reading_of(std::span<const std::uint8_t> original,
                                        std::span<const std::uint8_t> damaged, Dialect dialect,
                                        bool request) {
  if (dialect != Dialect::Ascii) {
    if (verify_check(damaged, dialect).ok || good_crc_prefix(damaged)) return std::nullopt;
    if (dialect == Dialect::Modbus && !modbus_shape_kept(original, damaged, request))
      return std::nullopt;
    return DamageReading::BadCheckFrame;
  }
  for (std::size_t i = 0; i < damaged.size(); ++i) {
    const std::uint8_t b = damaged[i];
    if (b != original[i] && (b == kEot || b == kEnq || b == kAck)) return std::nullopt;
  }
  // The checksum leaves the delimiters out, so only a frame-shaped result needs it bad.
  if (!ascii_frame_shaped(original, damaged)) return DamageReading::Noise;
  if (verify_check(damaged, dialect).ok) return std::nullopt;
  return DamageReading::BadCheckFrame;
}

namespace {

// Damages one byte of bytes[first..last].
FrameDamage damage_one_of(std::vector<std::uint8_t>& bytes, Dialect dialect, bool request,
                          SimRandom& random, std::int64_t first, std::int64_t last) {
  const std::vector<std::uint8_t> original = bytes;
  for (;;) {
    const auto at = static_cast<std::size_t>(random.between(first, last));
    const auto mask = random.percent(50) ? 1u << random.between(0, 7) : random.between(1, 255);
    bytes[at] = static_cast<std::uint8_t>(original[at] ^ mask);
    if (const auto reading = reading_of(original, bytes, dialect, request)) return {at, *reading};
    bytes[at] = original[at];
  }
}

}  // namespace

FrameDamage damage_frame(std::vector<std::uint8_t>& bytes, Dialect dialect, Role role,
                         SimRandom& random) {
  return damage_one_of(bytes, dialect, role == Role::Request, random, 0, std::ssize(bytes) - 1);
}

FrameDamage damage_reply_data(std::vector<std::uint8_t>& bytes, Dialect dialect,
                              SimRandom& random) {
  // RTU: station, function, byte count, data, CRC(2). ASCII: ACK, station(2), 'R',
  // address(4), data, checksum(4), EOT.
  const std::int64_t size = std::ssize(bytes);
  if (dialect == Dialect::Ascii) return damage_one_of(bytes, dialect, false, random, 8, size - 6);
  return damage_one_of(bytes, dialect, false, random, 3, size - 3);
}

std::uint8_t wire_station(std::span<const std::uint8_t> bytes, Dialect dialect) {
  if (dialect != Dialect::Ascii) return bytes[0];
  unsigned station = 0;
  const auto* text = reinterpret_cast<const char*>(bytes.data());
  std::from_chars(text + 1, text + 3, station, 16);
  return static_cast<std::uint8_t>(station);
}

std::uint8_t wire_function(std::span<const std::uint8_t> bytes, Dialect dialect) {
  return dialect == Dialect::Ascii ? fc::kAsciiRead : bytes[1];
}

}  // namespace pvtap::sim
