// Parsing and encoding of complete frames, and verification of their checks.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "pvtap/codec/frame.h"
#include "pvtap/codec/result.h"

namespace pvtap {

// FrameCheck: the verdict of a frame's checksum or CRC.
//   found/expected are the 16-bit values (RTU: the CRC; ASCII: the additive sum).
struct FrameCheck {
  bool ok = false;
  std::uint16_t found = 0;
  std::uint16_t expected = 0;
  // No check on the wire: the carrier (TCP, for Modbus/TCP) vouches for the bytes. ok is
  // true and found/expected are 0; outputs say "tcp", never "ok".
  bool carried = false;
};

// ParseOutcome: a parsed frame, or a short static description of why it is malformed.
using ParseOutcome = Result<Frame>;

// Parses one complete frame (exactly its bytes, check included) of a known dialect and role.
// The check is not judged here: a frame with a bad check still parses (see verify_check).
ParseOutcome parse_frame(std::span<const std::uint8_t> bytes, Dialect dialect, Role role);

// The same into `out`, a frame the caller keeps, for the hot path: a Result copies the
// frame's inline words. Returns why the bytes do not parse, or an empty view when they do
// (`out` is then unspecified).
std::string_view parse_frame_into(std::span<const std::uint8_t> bytes, Dialect dialect, Role role,
                                  Frame& out);

// The station and function a frame carries by their position alone, for a damaged frame
// that does not parse (its byte count lies): enough to match it and to report it. Fields an
// ASCII frame writes as hex digits are 0 when a digit is not one.
Frame frame_header(std::span<const std::uint8_t> bytes, Dialect dialect, Role role);

// The header of a frame sent so (a good check) that does not parse because its byte count
// lies: frame_header, and for a write of several registers or coils (0x0F 0x10) its start,
// quantity and byte count, which sit before the data the count miscounts.
Frame sent_header(std::span<const std::uint8_t> bytes, Dialect dialect, Role role);

// Verifies the checksum (ASCII) or CRC (RTU) of one complete frame.
// An ASCII frame whose checksum field is not hex has found = 0 and ok = false.
FrameCheck verify_check(std::span<const std::uint8_t> bytes, Dialect dialect);

// The check bytes as they should appear on the wire for `expected`
// (RTU: low byte, high byte; ASCII: four lowercase hex digits).
std::vector<std::uint8_t> check_wire_bytes(Dialect dialect, std::uint16_t expected);

// Appends the wire encoding of `frame` (with a correct check) to `out`.
// Returns false, appending nothing, when the frame's fields do not fit its kind.
bool encode_frame(const Frame& frame, std::vector<std::uint8_t>& out);

// Convenience: the wire encoding of `frame`, or an empty vector.
std::vector<std::uint8_t> encode_frame(const Frame& frame);

}  // namespace pvtap
