#include "pvtap/codec/frame_codec.h"

#include "dialects/dialect_module.h"
#include "pvtap/codec/function_codes.h"

namespace pvtap {

std::string_view parse_frame_into(std::span<const std::uint8_t> bytes, Dialect dialect, Role role,
                                  Frame& out) {
  return detail::dialect_module(dialect).parse(bytes, role, out);
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
  detail::dialect_module(dialect).read_header(bytes, f);
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
  return detail::dialect_module(dialect).verify_check(bytes);
}

std::vector<std::uint8_t> check_wire_bytes(Dialect dialect, std::uint16_t expected) {
  std::vector<std::uint8_t> out;
  detail::dialect_module(dialect).check_wire_bytes(expected, out);
  return out;
}

bool encode_frame(const Frame& frame, std::vector<std::uint8_t>& out) {
  return detail::dialect_module(frame.dialect).encode(frame, out);
}

std::vector<std::uint8_t> encode_frame(const Frame& frame) {
  std::vector<std::uint8_t> out;
  encode_frame(frame, out);
  return out;
}

}  // namespace pvtap
