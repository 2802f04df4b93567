#include "dialects/ascii/ascii_codec.h"

#include "codec/hex_digits.h"
#include "codec/wire_fields.h"
#include "pvtap/codec/checksums.h"
#include "pvtap/codec/function_codes.h"

namespace pvtap::detail {
namespace {

// Header shared by request and reply: lead byte, station(2), 'R', address(4).
constexpr std::size_t kHeaderLength = 8;
constexpr std::size_t kTrailerLength = 5;  // checksum(4) + EOT

void put_hex(std::vector<std::uint8_t>& out, unsigned value, int digits) {
  for (int i = digits - 1; i >= 0; --i) out.push_back(hex_char(value >> (4 * i)));
}

}  // namespace

ParseStatus parse_ascii(std::span<const std::uint8_t> b, Role role, Frame& f) {
  const bool request = role == Role::Request;
  if (request && b.size() != kAsciiRequestLength) return fail("ASCII request is not 15 bytes");
  if (!request && (b.size() < kAsciiReplyOverhead || (b.size() - kAsciiReplyOverhead) % 4 != 0)) {
    return fail("ASCII reply length is not 13 + 4 per word");
  }
  if (b[0] != (request ? kEnq : kAck)) return fail(request ? "missing ENQ" : "missing ACK");
  if (b.back() != kEot) return fail("missing EOT");
  if (b[3] != fc::kAsciiRead) return fail("command is not 'R'");
  const auto station = read_hex(b.subspan(1, 2));
  const auto start = read_hex(b.subspan(4, 4));
  if (!station || !start) return fail("non-hex character in a hex field");
  if (!read_hex(b.subspan(b.size() - kTrailerLength, 4))) return fail("non-hex checksum");

  f = make_frame(Dialect::Ascii, role, static_cast<std::uint8_t>(*station), fc::kAsciiRead);
  f.start = *start;
  const auto body = b.subspan(kHeaderLength, b.size() - kHeaderLength - kTrailerLength);
  if (request) {
    const auto count = read_hex(body);
    if (!count) return fail("non-hex character in a hex field");
    f.count = *count;
    return kParsed;
  }
  for (std::size_t i = 0; i < body.size(); i += 4) {
    const auto word = read_hex(body.subspan(i, 4));
    if (!word) return fail("non-hex character in a data word");
    if (!f.words.push_back(*word)) return fail("ASCII reply has more than 255 words");
  }
  return kParsed;
}

FrameCheck verify_ascii_check(std::span<const std::uint8_t> b) {
  FrameCheck c;
  if (b.size() < kTrailerLength + 1) return c;
  c.expected = AsciiChecksum::compute(b.subspan(1, b.size() - 1 - kTrailerLength));
  const auto found = read_hex(b.subspan(b.size() - kTrailerLength, 4));
  c.found = found.value_or(0);
  c.ok = found && *found == c.expected;
  return c;
}

bool encode_ascii(const Frame& f, std::vector<std::uint8_t>& out) {
  const bool request = f.role == Role::Request;
  if (f.function != fc::kAsciiRead || !f.start) return false;
  if (request && (!f.count || *f.count > 0xFF || !f.words.empty())) return false;
  if (!request && (f.count || f.words.size() > 255)) return false;
  const std::size_t begin = out.size();
  out.push_back(request ? kEnq : kAck);
  put_hex(out, f.station, 2);
  out.push_back(fc::kAsciiRead);
  put_hex(out, *f.start, 4);
  if (request) put_hex(out, *f.count, 2);
  for (auto w : f.words) put_hex(out, w, 4);
  const auto sum = AsciiChecksum::compute(std::span(out).subspan(begin + 1));
  put_hex(out, sum, 4);
  out.push_back(kEot);
  return true;
}

}  // namespace pvtap::detail
