#include "dialects/hybrid/hybrid_codec.h"

#include "pvtap/codec/function_codes.h"

namespace pvtap::detail {
namespace {

constexpr std::size_t kDeviceNumberLength = 4;

}  // namespace

ParseStatus parse_hybrid_request(std::span<const std::uint8_t> b, Frame& f) {
  if (b.size() != kFixedRequestLength) return fail("Hybrid request is not 8 bytes");
  f.start = be16(b, 2);
  if (f.function == fc::kHybridWriteParameter) {
    f.words.push_back(be16(b, 4));
  } else if (fc::is_hybrid_range_request(f.function)) {
    f.count = be16(b, 4);
  } else {
    return fail("not a Hybrid request function code");
  }
  return kParsed;
}

ParseStatus parse_hybrid_reply(std::span<const std::uint8_t> b, Frame& f) {
  const auto body = counted_body(b, f);
  if (!body) return fail("Hybrid reply length disagrees with its byte count");
  if (body->size() < kDeviceNumberLength) return fail("Hybrid reply shorter than a device number");
  const auto& d = *body;
  f.device = DeviceNumber{d[0], static_cast<std::uint32_t>((d[1] << 16) | (d[2] << 8) | d[3])};
  const auto rest = d.subspan(kDeviceNumberLength);
  const bool fixed_echo = rest.size() == 4;
  if (fixed_echo && f.function == fc::kHybridWriteParameter) {
    f.start = be16(rest, 0);
    f.words.push_back(be16(rest, 2));
  } else if (fixed_echo &&
             (f.function == fc::kHybridRestoreFactory || f.function == fc::kHybridError)) {
    f.start = be16(rest, 0);
    f.count = be16(rest, 2);
  } else if (!read_words(rest, f.words)) {
    return fail("Hybrid reply data is not whole 16-bit registers");
  }
  return kParsed;
}

void encode_hybrid_reply_body(const Frame& f, std::vector<std::uint8_t>& body) {
  const auto& d = *f.device;
  body.push_back(d.type_code);
  body.push_back(static_cast<std::uint8_t>(d.serial >> 16));
  body.push_back(static_cast<std::uint8_t>(d.serial >> 8));
  body.push_back(static_cast<std::uint8_t>(d.serial));
  if (f.start) put16(body, *f.start);
  if (f.count) put16(body, *f.count);
  for (auto w : f.words) put16(body, w);
}

}  // namespace pvtap::detail
