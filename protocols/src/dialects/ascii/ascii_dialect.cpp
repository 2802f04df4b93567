// The ASCII dialect's record in the table of dialects (PROTOCOLS.md section 1).
#include "codec/hex_digits.h"
#include "dialects/ascii/ascii_codec.h"
#include "dialects/dialect_module.h"
#include "pvtap/codec/function_codes.h"
#include "registers/value_placement.h"

namespace pvtap::embedded {
extern const unsigned char map_ascii[];
extern const std::size_t map_ascii_size;
}  // namespace pvtap::embedded

namespace pvtap::detail {
namespace {

// ENQ/ACK, the station as two hex digits, the command character.
void read_ascii_header(std::span<const std::uint8_t> bytes, Frame& out) {
  if (bytes.size() <= 3) return;
  out.station = static_cast<std::uint8_t>(read_hex(bytes.subspan(1, 2)).value_or(0));
  out.function = bytes[3];
}

// Four lowercase hex digits, the most significant first.
void ascii_check_wire_bytes(std::uint16_t expected, std::vector<std::uint8_t>& out) {
  out.insert(out.end(), {hex_char(expected >> 12u), hex_char(expected >> 8u),
                         hex_char(expected >> 4u), hex_char(expected)});
}

// Words in the reply = the count of the request.
std::optional<CountComparison> compare_ascii(const FrameSummary& request,
                                             const FrameSummary& reply) {
  if (!request.count) return std::nullopt;
  return CountComparison{unsigned{*request.count}, unsigned{reply.word_count}, CountUnit::Words};
}

// A read reply's words sit at the start it repeats from its request.
DecodeReport ascii_values(const RegisterDecoder& decoder, const Frame& frame, const Frame* request,
                          std::vector<DecodedValue>& out) {
  if (frame.role != Role::Response || !frame.start) return nothing(ValueOrigin::ReadReply);
  DecodeReport report =
      decoder.place(Dialect::Ascii, *frame.start, frame.words.span(), ValueOrigin::ReadReply, out);
  note_request_fit(report, frame, request);
  return report;
}

}  // namespace

extern const DialectModule kAsciiDialect{
    .dialect = Dialect::Ascii,
    .title = "ASCII",
    .short_title = "ASCII",
    .check_name = "checksum",
    .error_reply_name = "",
    .rtu_framed = false,
    .parse = parse_ascii,
    .read_header = read_ascii_header,
    .verify_check = verify_ascii_check,
    .check_wire_bytes = ascii_check_wire_bytes,
    .encode = encode_ascii,
    .function_name = [](std::uint8_t f) -> std::string_view {
      return f == fc::kAsciiRead ? "read" : "unknown";
    },
    .exception_name = [](std::uint8_t code) { return fc::exception_name(code); },
    .builtin_map_text = []() -> std::string_view {
      return {reinterpret_cast<const char*>(embedded::map_ascii), embedded::map_ascii_size};
    },
    .reply_family = Dialect::Ascii,
    .reply_kind = [](std::uint8_t) { return ReplyKind::Normal; },
    .answered_by_gateway_exception = false,
    .reply_repeats_start = true,
    .reply_is_echo = [](std::uint8_t) { return false; },
    .compare_reply_count = compare_ascii,
    .decimal_register_ids = false,
    .register_address_step = 2,
    .answered_broadcast_station = -1,
    .reply_may_be_modbus_family = false,
    .decode_values = ascii_values,
};

}  // namespace pvtap::detail
