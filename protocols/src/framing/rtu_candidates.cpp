#include "framing/rtu_candidates.h"

#include "codec/wire_fields.h"
#include "framing/candidate_reader.h"

#include "pvtap/codec/function_codes.h"

namespace pvtap::detail {
namespace {

constexpr unsigned kMaxReadCount = 125;  // a reply must fit its data in one byte count

using Reader = CandidateReader;

void hybrid_request(Reader& r, std::uint8_t f) {
  if (f == fc::kHybridError) return;
  if (r.strict && fc::is_hybrid_range_request(f) && r.has(5)) {
    const unsigned count = r.word(4);
    if (count == 0 || count > kMaxReadCount) return;
  }
  r.add(kFixedRequestLength, Role::Request);
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
  r.add(kFixedRequestLength, Role::Request);
}

bool is_write(std::uint8_t f) {
  return f == fc::kGslWriteSingle || f == fc::kGslWriteMultiple;
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
    r.add(kFixedRequestLength, Role::Response);
  } else {
    r.add(kFixedRequestLength, Role::Response);
  }
}

}  // namespace

void add_rtu_candidates(std::span<const std::uint8_t> b, RoleHint hint, DialectSet dialects,
                        Plausibility plausibility, CandidateList& out) {
  const bool strict = plausibility == Plausibility::Require;
  // A plain Modbus write may be broadcast to station 0; no other frame names it.
  const bool broadcast_allowed = dialects.contains(Dialect::Modbus);
  if (b.size() < 2) {
    if (strict && !b.empty() && b[0] == 0 && !broadcast_allowed) return;
    out.need_header = 2 - b.size();
    return;
  }
  const std::uint8_t f = b[1];
  // Most positions a hunt tries hold no function code of any dialect.
  if (fc::detail::kFunctionKinds.of[f] == 0) return;
  const bool requests = hint != RoleHint::Response;
  const bool responses = hint != RoleHint::Request;
  if (dialects.contains(Dialect::Hybrid) && fc::is_hybrid_function(f) && !(strict && b[0] == 0)) {
    Reader r{b, Dialect::Hybrid, strict, out};
    if (requests) hybrid_request(r, f);
    if (responses) hybrid_response(r, f);
  }
  if (strict && b[0] > fc::kLastModbusStation) return;
  // The codes GSL shares with Modbus are read once, as GSL when GSL is asked for: which of
  // the two a station speaks is the session's decision (station_dialects.h).
  const bool gsl_code = fc::is_gsl_function(f);
  if (gsl_code && dialects.modbus_family()) {
    const Dialect d = dialects.contains(Dialect::Gsl) ? Dialect::Gsl : Dialect::Modbus;
    Reader r{b, d, strict, out};
    const bool broadcast = b[0] == fc::kModbusBroadcast;
    if (requests && (!strict || !broadcast || (broadcast_allowed && is_write(f)))) {
      gsl_request(r, f);
    }
    if (responses && !(strict && broadcast)) gsl_response(r, f);
    return;
  }
  if (!dialects.contains(Dialect::Modbus) || !fc::is_modbus_function(f)) return;
  // With some fifty more codes (exceptions included), a run of noise between two frames
  // would often pass for a damaged frame: a reading of these codes whose fields break the
  // specification's ranges, or cannot be judged, is a frame only with a good check
  // (CandidateReader::reject_implausible), and one from an impossible station never.
  if (b[0] > fc::kLastModbusStation) return;
  Reader r{b, Dialect::Modbus, strict, out};
  if (requests) add_modbus_request(r, f);
  if (responses && b[0] != fc::kModbusBroadcast) add_modbus_response(r, f);
}

}  // namespace pvtap::detail
