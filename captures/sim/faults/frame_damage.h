// Frame damage: one bit or one byte of an encoded frame changed, as a line changes it, and
// what a reader can still delimit of the result (the ground truth's rules, decided here from
// the bytes the simulator damaged, never by asking pvtap's reassembler).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "pvtap/codec/dialect.h"
#include "sim_random.h"

namespace pvtap::sim {

// What a reader sees of a damaged frame between pinned ends.
enum class DamageReading {
  BadCheckFrame,  // a frame of the original length with a bad check
  Noise,          // ASCII only: a delimiter or a hex digit was lost, so no frame at all
};

struct FrameDamage {
  std::size_t at = 0;  // the damaged byte
  DamageReading reading = DamageReading::BadCheckFrame;
};

// How a reader reads `damaged` (one byte of the good frame `original` changed), or nullopt
// when a reader could read it more than one way and the damage must be drawn again:
// - RTU: a bad-check frame, unless a shorter prefix of it has a good CRC (a good frame
//   hidden at the pinned start);
// - ASCII: a bad-check frame when ENQ/ACK, 'R', EOT and every hex digit survive, noise
//   otherwise; ambiguous when the new byte is itself a delimiter (EOT, ENQ, ACK) or a
//   frame-shaped result still has a good check (a case flip in the checksum);
// - plain Modbus (`request`: the frame is one): ambiguous too when the function byte changed
//   or a request's quantity left the specification's range (a frame of another length, or
//   noise, is as good a reading).
std::optional<DamageReading> reading_of(std::span<const std::uint8_t> original,
                                        std::span<const std::uint8_t> damaged, Dialect dialect,
                                        bool request = false);

// XORs any one byte of `bytes` (every header field included) with one bit or with a random
// nonzero byte, 50/50, drawing again until reading_of has one answer.
FrameDamage damage_frame(std::vector<std::uint8_t>& bytes, Dialect dialect, Role role,
                         SimRandom& random);
// The same for one byte of a read reply's data only: station, function, byte count (ASCII:
// address) and check stay as sent, so the frame's length is still written in its header.
FrameDamage damage_reply_data(std::vector<std::uint8_t>& bytes, Dialect dialect, SimRandom& random);

// Station and function of a damaged frame as its bytes now say (BadCheckFrame readings only:
// an ASCII station is still two hex digits).
std::uint8_t wire_station(std::span<const std::uint8_t> bytes, Dialect dialect);
std::uint8_t wire_function(std::span<const std::uint8_t> bytes, Dialect dialect);

}  // namespace pvtap::sim
