#include "dialects/ascii/ascii_candidates.h"

#include "codec/hex_digits.h"
#include "dialects/ascii/ascii_codec.h"
#include "pvtap/codec/function_codes.h"

namespace pvtap::detail {
namespace {

bool is_hex(std::uint8_t c) {
  return hex_digit_value(c) >= 0;
}

// Station(2) 'R' address(4): the eight bytes both kinds share, checked as far as present.
bool header_holds(std::span<const std::uint8_t> b) {
  const std::size_t n = b.size() < 8 ? b.size() : 8;
  for (std::size_t i = 1; i < n; ++i) {
    if (i == 3 ? b[i] != fc::kAsciiRead : !is_hex(b[i])) return false;
  }
  return true;
}

void add_request(std::span<const std::uint8_t> b, CandidateList& out) {
  const std::size_t n = b.size() < kAsciiRequestLength ? b.size() : kAsciiRequestLength;
  for (std::size_t i = 8; i < n; ++i) {
    if (i + 1 == kAsciiRequestLength ? b[i] != kEot : !is_hex(b[i])) return;
  }
  out.add({kAsciiRequestLength, Dialect::Ascii, Role::Request, false});
}

// A reply's length is known only at its EOT, which cannot occur inside hex digits.
void add_reply(std::span<const std::uint8_t> b, CandidateList& out) {
  const std::size_t limit = b.size() < kMaxFrameLength ? b.size() : kMaxFrameLength;
  for (std::size_t i = 8; i < limit; ++i) {
    if (b[i] == kEot) {
      const std::size_t length = i + 1;
      if (length >= kAsciiReplyOverhead && (length - kAsciiReplyOverhead) % 4 == 0) {
        out.add({length, Dialect::Ascii, Role::Response, false});
      }
      return;
    }
    if (!is_hex(b[i])) return;
  }
  if (limit < kMaxFrameLength) {
    const std::size_t least = b.size() < kAsciiReplyOverhead ? kAsciiReplyOverhead : b.size() + 1;
    const std::size_t need = least - b.size();
    if (out.need_header == 0 || need < out.need_header) out.need_header = need;
  }
}

}  // namespace

void add_ascii_candidates(std::span<const std::uint8_t> b, RoleHint hint, CandidateList& out) {
  if (b.empty() || (b[0] != kEnq && b[0] != kAck) || !header_holds(b)) return;
  if (b[0] == kEnq && hint != RoleHint::Response) add_request(b, out);
  if (b[0] == kAck && hint != RoleHint::Request) add_reply(b, out);
}

}  // namespace pvtap::detail
