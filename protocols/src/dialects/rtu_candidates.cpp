#include "dialects/rtu_candidates.h"

#include "codec/wire_fields.h"
#include "dialects/hybrid/hybrid_candidates.h"
#include "dialects/modbus/gsl_candidates.h"
#include "framing/candidate_reader.h"

#include "pvtap/codec/function_codes.h"

namespace pvtap::detail {
namespace {

using Reader = CandidateReader;

bool is_write(std::uint8_t f) {
  return f == fc::kGslWriteSingle || f == fc::kGslWriteMultiple;
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
    if (requests) add_hybrid_request(r, f);
    if (responses) add_hybrid_response(r, f);
  }
  if (strict && b[0] > fc::kLastModbusStation) return;
  // The codes GSL shares with Modbus are read once, as GSL when GSL is asked for: which of
  // the two a station speaks is the session's decision (dialects/modbus/station_dialects.h).
  const bool gsl_code = fc::is_gsl_function(f);
  if (gsl_code && dialects.modbus_family()) {
    const Dialect d = dialects.contains(Dialect::Gsl) ? Dialect::Gsl : Dialect::Modbus;
    Reader r{b, d, strict, out};
    const bool broadcast = b[0] == fc::kModbusBroadcast;
    if (requests && (!strict || !broadcast || (broadcast_allowed && is_write(f)))) {
      add_gsl_request(r, f);
    }
    if (responses && !(strict && broadcast)) add_gsl_response(r, f);
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

namespace pvtap::fc {

std::optional<Dialect> rtu_dialect_of(std::uint8_t f) {
  if (is_hybrid_function(f)) return Dialect::Hybrid;
  if (is_gsl_function(f)) return Dialect::Gsl;
  if (is_modbus_function(f)) return Dialect::Modbus;
  return std::nullopt;
}

}  // namespace pvtap::fc
