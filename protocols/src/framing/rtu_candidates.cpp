#include "framing/rtu_candidates.h"

#include "pvtap/codec/function_codes.h"

namespace pvtap::detail {
namespace {

constexpr std::size_t kFixedLength = 8;
constexpr unsigned kMaxReadCount = 125;  // a reply must fit its data in one byte count

// Collects readings; a reading whose length needs a byte not yet seen records that need.
// `strict` rules out readings with implausible fields; the length rules hold either way.
struct Reader {
  std::span<const std::uint8_t> b;
  Dialect dialect;
  bool strict;
  CandidateList& out;

  bool has(std::size_t i) {
    if (i < b.size()) return true;
    const std::size_t need = i + 1 - b.size();
    if (out.need_header == 0 || need < out.need_header) out.need_header = need;
    return false;
  }
  unsigned word(std::size_t at) const { return (unsigned{b[at]} << 8) | b[at + 1]; }
  void add(std::size_t length, Role role) { out.add({length, dialect, role}); }
};

bool is_hybrid_read(std::uint8_t f) {
  return f == fc::kHybridDeviceInfo || f == fc::kHybridRunningData || f == fc::kHybridSettings ||
         f == fc::kHybridManufacturer || f == fc::kHybridRestoreFactory;
}

void hybrid_request(Reader& r, std::uint8_t f) {
  if (f == fc::kHybridError) return;
  if (r.strict && is_hybrid_read(f) && r.has(5)) {
    const unsigned count = r.word(4);
    if (count == 0 || count > kMaxReadCount) return;
  }
  r.add(kFixedLength, Role::Request);
}

// Every reply carries the 4-byte device number and then whole registers; write echoes,
// restore confirmations and error replies always carry exactly two words after it.
void hybrid_response(Reader& r, std::uint8_t f) {
  if (r.strict && r.b[0] == fc::kHybridBroadcast) return;
  if (!r.has(2)) return;
  const std::size_t n = r.b[2];
  const bool fixed =
      f == fc::kHybridWriteParameter || f == fc::kHybridRestoreFactory || f == fc::kHybridError;
  if (r.strict && (n < 4 || n % 2 != 0 || (fixed && n != 8))) return;
  r.add(5 + n, Role::Response);
}

void gsl_request(Reader& r, std::uint8_t f) {
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
  r.add(kFixedLength, Role::Request);
}

// Exception codes defined by Modbus (the seed uses 1, 2, 3 and 6).
constexpr std::uint8_t kMaxExceptionCode = 0x0B;

void gsl_response(Reader& r, std::uint8_t f) {
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
    r.add(kFixedLength, Role::Response);
  } else {
    r.add(kFixedLength, Role::Response);
  }
}

}  // namespace

void add_rtu_candidates(std::span<const std::uint8_t> b, RoleHint hint, DialectSet dialects,
                        Plausibility plausibility, CandidateList& out) {
  const bool strict = plausibility == Plausibility::Require;
  if (b.size() < 2) {
    if (strict && !b.empty() && b[0] == 0) return;
    out.need_header = 2 - b.size();
    return;
  }
  const std::uint8_t f = b[1];
  const auto dialect = fc::rtu_dialect_of(f);
  if (!dialect || !dialects.contains(*dialect) || (strict && b[0] == 0)) return;
  Reader r{b, *dialect, strict, out};
  const bool requests = hint != RoleHint::Response;
  const bool responses = hint != RoleHint::Request;
  if (*dialect == Dialect::Hybrid) {
    if (requests) hybrid_request(r, f);
    if (responses) hybrid_response(r, f);
    return;
  }
  if (strict && b[0] > 247) return;
  if (requests) gsl_request(r, f);
  if (responses) gsl_response(r, f);
}

}  // namespace pvtap::detail
