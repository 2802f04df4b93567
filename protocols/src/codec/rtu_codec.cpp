#include "codec/rtu_codec.h"

#include "codec/wire_fields.h"
#include "dialects/hybrid/hybrid_codec.h"
#include "pvtap/codec/checksums.h"
#include "pvtap/codec/function_codes.h"

namespace pvtap::detail {
namespace {

constexpr std::size_t kCrcLength = 2;

}  // namespace

bool encode_rtu_fields(const Frame& f, std::vector<std::uint8_t>& out) {
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

bool append_crc(std::size_t begin, std::vector<std::uint8_t>& out) {
  const auto crc = Crc16Modbus::compute(std::span(out).subspan(begin));
  out.push_back(static_cast<std::uint8_t>(crc & 0xFFu));
  out.push_back(static_cast<std::uint8_t>(crc >> 8));
  return true;
}

std::string_view unknown_function(std::uint8_t function) {
  // A code no dialect defines (Modbus/TCP carries any code whole) says so, not "another".
  return fc::detail::kFunctionKinds.of[function] == 0 ? "function code without a public layout"
                                                      : "function code of another dialect";
}

}  // namespace pvtap::detail
