// Length rules of GSL's function codes, which plain Modbus shares (PROTOCOLS.md section 3),
// inline: they run at every position a hunt tries (private).
#pragma once

#include <cstdint>

#include "codec/wire_fields.h"
#include "framing/candidate_reader.h"
#include "pvtap/codec/function_codes.h"

namespace pvtap::detail {

// Exception codes defined by Modbus (the seed uses 1, 2, 3 and 6).
inline constexpr std::uint8_t kMaxExceptionCode = 0x0B;

inline void add_gsl_request(CandidateReader& r, std::uint8_t f) {
  if (fc::is_gsl_exception(f)) return;
  if (f == fc::kGslWriteMultiple) {
    if (!r.has(6)) return;
    const unsigned count = r.word(4);
    if (r.strict && (count == 0 || count > 123 || r.b[6] != 2 * count)) return;
    r.add(9 + std::size_t{r.b[6]}, Role::Request);
    return;
  }
  if (r.strict && f != fc::kGslWriteSingle && r.has(5)) {
    const unsigned count = r.word(4);
    if (count == 0 || count > kMaxReadCount) return;
  }
  r.add(kFixedRequestLength, Role::Request);
}

inline void add_gsl_response(CandidateReader& r, std::uint8_t f) {
  if (fc::is_gsl_exception(f)) {
    if (r.strict && r.has(2) && (r.b[2] == 0 || r.b[2] > kMaxExceptionCode)) return;
    r.add(5, Role::Response);
  } else if (f == fc::kGslReadHolding || f == fc::kGslReadInput) {
    if (!r.has(2)) return;
    const std::size_t n = r.b[2];
    if (r.strict && (n == 0 || n % 2 != 0)) return;
    r.add(5 + n, Role::Response);
  } else if (f == fc::kGslWriteMultiple) {
    if (r.strict && r.has(5)) {
      const unsigned count = r.word(4);
      if (count == 0 || count > 123) return;
    }
    r.add(kFixedRequestLength, Role::Response);
  } else {
    r.add(kFixedRequestLength, Role::Response);
  }
}

}  // namespace pvtap::detail
