#include "codec/rtu_codec.h"

#include "codec/wire_fields.h"
#include "dialects/hybrid/hybrid_codec.h"
#include "dialects/modbus/gsl_codec.h"
#include "dialects/modbus/modbus_codec.h"
#include "pvtap/codec/checksums.h"
#include "pvtap/codec/function_codes.h"

namespace pvtap::detail {
namespace {

constexpr std::size_t kCrcLength = 2;

bool encode_body(const Frame& f, std::vector<std::uint8_t>& out) {
  const bool request = f.role == Role::Request;
  if (fc::is_gsl_exception(f.function) && modbus_family(f.dialect)) {
    if (request || !f.exception_code) return false;
    out.push_back(*f.exception_code);
    return true;
  }
  if (!request && (f.byte_count || f.device)) {  // counted reply: addr fc n data
    std::vector<std::uint8_t> body;
    if (f.device)
      encode_hybrid_reply_body(f, body);
    else
      for (auto w : f.words) put16(body, w);
    if (body.size() > 0xFF) return false;
    out.push_back(static_cast<std::uint8_t>(body.size()));
    out.insert(out.end(), body.begin(), body.end());
    return true;
  }
  if (!f.start) return false;
  put16(out, *f.start);
  if (f.count) put16(out, *f.count);
  if (request && f.function == fc::kGslWriteMultiple) {
    if (f.words.size() * 2 > 0xFF) return false;
    out.push_back(f.byte_count.value_or(static_cast<std::uint8_t>(f.words.size() * 2)));
  }
  for (auto w : f.words) put16(out, w);
  return true;
}

}  // namespace

namespace {

// A gateway's own exception (0x0A, 0x0B) answers whatever it forwarded, a function of another
// dialect included (a Hybrid read through a Modbus/TCP gateway): station, fc|0x80, code, CRC.
bool gateway_exception(std::span<const std::uint8_t> b, Dialect dialect, Role role) {
  return modbus_family(dialect) && role == Role::Response && b.size() == 5 &&
         fc::is_gsl_exception(b[1]) &&
         (b[2] == fc::kGatewayPathUnavailable || b[2] == fc::kGatewayTargetNoResponse);
}

// A user-defined code of plain Modbus (PROTOCOLS.md section 6): no public layout, so its
// bytes are kept as they came; the framing finds such a frame only between pinned ends.
bool user_defined(Dialect dialect, std::uint8_t function) {
  return dialect == Dialect::Modbus && fc::is_user_defined_function(function);
}

}  // namespace

ParseStatus parse_rtu(std::span<const std::uint8_t> b, Dialect dialect, Role role, Frame& f) {
  if (b.size() < 4) return fail("RTU frame shorter than 4 bytes");
  f = make_frame(dialect, role, b[0], b[1]);
  if (!fc::dialect_has_function(dialect, f.function) && !gateway_exception(b, dialect, role) &&
      !user_defined(dialect, f.function)) {
    // A code no dialect defines (Modbus/TCP carries any code whole) says so, not "another".
    return fail(fc::detail::kFunctionKinds.of[f.function] == 0
                    ? "function code without a public layout"
                    : "function code of another dialect");
  }
  if (dialect == Dialect::Hybrid) {
    return role == Role::Request ? parse_hybrid_request(b, f) : parse_hybrid_reply(b, f);
  }
  if (fc::is_gsl_function(f.function)) {
    return role == Role::Request ? parse_gsl_request(b, f) : parse_gsl_reply(b, f);
  }
  if (fc::is_gsl_exception(f.function)) {
    if (role == Role::Request) return fail("an exception is never a request");
    return parse_gsl_reply(b, f);
  }
  return role == Role::Request ? parse_modbus_request(b, f) : parse_modbus_reply(b, f);
}

void read_rtu_header(std::span<const std::uint8_t> b, Frame& out) {
  if (b.size() <= 1) return;
  out.station = b[0];
  out.function = b[1];
}

// The CRC's low byte first.
void rtu_check_wire_bytes(std::uint16_t expected, std::vector<std::uint8_t>& out) {
  out.push_back(static_cast<std::uint8_t>(expected & 0xFFu));
  out.push_back(static_cast<std::uint8_t>(expected >> 8));
}

FrameCheck verify_rtu_check(std::span<const std::uint8_t> b) {
  FrameCheck c;
  if (b.size() < kCrcLength + 1) return c;
  c.expected = Crc16Modbus::compute(b.first(b.size() - kCrcLength));
  c.found = static_cast<std::uint16_t>(b[b.size() - 2] | (b[b.size() - 1] << 8));
  c.ok = c.found == c.expected;
  return c;
}

bool encode_rtu(const Frame& f, std::vector<std::uint8_t>& out) {
  if (!fc::dialect_has_function(f.dialect, f.function) && !user_defined(f.dialect, f.function)) {
    return false;
  }
  const std::size_t begin = out.size();
  out.push_back(f.station);
  out.push_back(f.function);
  const bool plain_modbus = f.dialect != Dialect::Hybrid && !fc::is_gsl_function(f.function) &&
                            !fc::is_gsl_exception(f.function);
  if (!(plain_modbus ? encode_modbus_body(f, out) : encode_body(f, out))) {
    out.resize(begin);
    return false;
  }
  const auto crc = Crc16Modbus::compute(std::span(out).subspan(begin));
  out.push_back(static_cast<std::uint8_t>(crc & 0xFFu));
  out.push_back(static_cast<std::uint8_t>(crc >> 8));
  return true;
}

}  // namespace pvtap::detail
