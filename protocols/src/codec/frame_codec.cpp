#include "pvtap/codec/frame_codec.h"

#include "codec/hex_digits.h"
#include "codec/rtu_codec.h"
#include "dialects/ascii/ascii_codec.h"
#include "pvtap/codec/function_codes.h"

namespace pvtap {

std::string_view parse_frame_into(std::span<const std::uint8_t> bytes, Dialect dialect, Role role,
                                  Frame& out) {
  if (dialect == Dialect::Ascii) return detail::parse_ascii(bytes, role, out);
  return detail::parse_rtu(bytes, dialect, role, out);
}

ParseOutcome parse_frame(std::span<const std::uint8_t> bytes, Dialect dialect, Role role) {
  Frame f;
  const std::string_view why = parse_frame_into(bytes, dialect, role, f);
  if (!why.empty()) return ParseOutcome::failure(why);
  return f;
}

Frame frame_header(std::span<const std::uint8_t> bytes, Dialect dialect, Role role) {
  Frame f;
  f.dialect = dialect;
  f.role = role;
  if (dialect == Dialect::Ascii) {
    // ENQ/ACK, station as two hex digits, the command character.
    if (bytes.size() > 3) {
      f.station = static_cast<std::uint8_t>(detail::read_hex(bytes.subspan(1, 2)).value_or(0));
      f.function = bytes[3];
    }
    return f;
  }
  if (bytes.size() > 1) {
    f.station = bytes[0];
    f.function = bytes[1];
  }
  return f;
}

Frame sent_header(std::span<const std::uint8_t> bytes, Dialect dialect, Role role) {
  Frame f = frame_header(bytes, dialect, role);
  const bool counted_write =
      f.function == fc::kGslWriteMultiple || f.function == fc::kWriteMultipleCoils;
  if (modbus_family(dialect) && role == Role::Request && counted_write && bytes.size() > 6) {
    f.start = static_cast<std::uint16_t>(bytes[2] << 8 | bytes[3]);
    f.count = static_cast<std::uint16_t>(bytes[4] << 8 | bytes[5]);
    f.byte_count = bytes[6];
  }
  return f;
}

FrameCheck verify_check(std::span<const std::uint8_t> bytes, Dialect dialect) {
  if (dialect == Dialect::Ascii) return detail::verify_ascii_check(bytes);
  return detail::verify_rtu_check(bytes);
}

std::vector<std::uint8_t> check_wire_bytes(Dialect dialect, std::uint16_t expected) {
  if (dialect == Dialect::Ascii) {
    return {detail::hex_char(expected >> 12u), detail::hex_char(expected >> 8u),
            detail::hex_char(expected >> 4u), detail::hex_char(expected)};
  }
  return {static_cast<std::uint8_t>(expected & 0xFFu), static_cast<std::uint8_t>(expected >> 8)};
}

bool encode_frame(const Frame& frame, std::vector<std::uint8_t>& out) {
  if (frame.dialect == Dialect::Ascii) return detail::encode_ascii(frame, out);
  return detail::encode_rtu(frame, out);
}

std::vector<std::uint8_t> encode_frame(const Frame& frame) {
  std::vector<std::uint8_t> out;
  encode_frame(frame, out);
  return out;
}

}  // namespace pvtap
