#include "dialects/modbus/gsl_codec.h"

#include "pvtap/codec/function_codes.h"

namespace pvtap::detail {

ParseStatus parse_gsl_request(std::span<const std::uint8_t> b, Frame& f) {
  if (f.function == fc::kGslWriteMultiple) {
    if (b.size() < 9 || b.size() != 9u + b[6]) return fail("GSL 0x10 length disagrees with n");
    f.start = be16(b, 2);
    f.count = be16(b, 4);
    f.byte_count = b[6];
    if (!read_words(b.subspan(7, b[6]), f.words))
      return fail("GSL 0x10 data is not whole registers");
    return kParsed;
  }
  if (b.size() != kFixedRequestLength) return fail("GSL request is not 8 bytes");
  f.start = be16(b, 2);
  if (f.function == fc::kGslWriteSingle) {
    f.words.push_back(be16(b, 4));
  } else if (f.function == fc::kGslReadHolding || f.function == fc::kGslReadInput) {
    f.count = be16(b, 4);
  } else {
    return fail("not a GSL request function code");
  }
  return kParsed;
}

ParseStatus parse_gsl_reply(std::span<const std::uint8_t> b, Frame& f) {
  if (fc::is_gsl_exception(f.function)) {
    if (b.size() != 5) return fail("GSL exception is not 5 bytes");
    f.exception_code = b[2];
    return kParsed;
  }
  if (f.function == fc::kGslReadHolding || f.function == fc::kGslReadInput) {
    const auto body = counted_body(b, f);
    if (!body) return fail("GSL reply length disagrees with its byte count");
    if (!read_words(*body, f.words)) return fail("GSL reply data is not whole registers");
    return kParsed;
  }
  if (b.size() != kFixedRequestLength) return fail("GSL write reply is not 8 bytes");
  f.start = be16(b, 2);
  if (f.function == fc::kGslWriteSingle) {
    f.words.push_back(be16(b, 4));
  } else if (f.function == fc::kGslWriteMultiple) {
    f.count = be16(b, 4);
  } else {
    return fail("not a GSL reply function code");
  }
  return kParsed;
}

}  // namespace pvtap::detail
