#include "session/station_dialects.h"

#include <algorithm>
#include <iterator>

#include "pvtap/codec/function_codes.h"

namespace pvtap::detail {
namespace {

// The wire addresses of every register of a map, as sorted runs of consecutive addresses.
std::vector<StationDialects::Run> wire_runs(const RegisterMap& map, const DecoderOptions& options) {
  std::vector<std::uint16_t> out;
  for (const RegisterDef& def : map.registers()) {
    const unsigned span = unsigned{def.words} * def.repeat;
    for (unsigned i = 0; i < span && def.address + i <= 0xFFFFu; ++i) {
      const auto written = static_cast<std::uint16_t>(def.address + i);
      if (auto wire = wire_address_of(map.dialect(), written, options.gsl_ids)) {
        out.push_back(*wire);
      }
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  std::vector<StationDialects::Run> runs;
  for (const std::uint16_t a : out) {
    if (!runs.empty() && unsigned{runs.back().last} + 1 == a) {
      runs.back().last = a;
    } else {
      runs.push_back({a, a});
    }
  }
  return runs;
}

bool addresses_registers(std::uint8_t f) {
  return f == fc::kGslReadHolding || f == fc::kGslReadInput || f == fc::kGslWriteSingle ||
         f == fc::kGslWriteMultiple;
}

}  // namespace

StationDialects::StationDialects(DialectSet enabled, const RegisterDecoder& decoder)
    : choose_(enabled.contains(Dialect::Gsl) && enabled.contains(Dialect::Modbus)),
      gsl_runs_(wire_runs(decoder.map(Dialect::Gsl), decoder.options())) {
  for (std::size_t s = 0; s < kStations; ++s) {
    const RegisterMap* own = decoder.station_map(static_cast<std::uint8_t>(s));
    if (own != nullptr && modbus_family(own->dialect())) forced_[s] = own->dialect();
  }
}

// Every register asked for is one the GSL map has. Overlapping it is not enough: a meter
// reading 1024..1039 is not a KSTAR inverter because 1030..1033 are its alarm words.
bool StationDialects::addresses_gsl_map(std::uint16_t start, std::uint16_t count) const {
  const unsigned last = unsigned{start} + std::max<unsigned>(count, 1) - 1;
  const auto after = std::upper_bound(gsl_runs_.begin(), gsl_runs_.end(), start,
                                      [](std::uint16_t a, const Run& r) { return a < r.first; });
  if (after == gsl_runs_.begin()) return false;
  const Run& run = *std::prev(after);
  return start >= run.first && last <= run.last;
}

// What a frame says of its station by itself: only a request naming registers says anything.
std::optional<Dialect> StationDialects::evidence(const Frame& f) const {
  if (f.role != Role::Request || !addresses_registers(f.function) || !f.start) {
    return std::nullopt;
  }
  const std::uint16_t count = f.count.value_or(1);
  return addresses_gsl_map(*f.start, count) ? Dialect::Gsl : Dialect::Modbus;
}

// A frame of a dialect of its own says which its station speaks; a GSL/Modbus frame only
// when its registers say it. A station's first frame claims weakly: a later claim replaces it
// without a change being reported (a logger probing a GSL inverter with 0x2B first).
StationDialects::Claim StationDialects::claim_of(const Frame& frame, Dialect label) const {
  if (!modbus_family(label) || forced_[frame.station]) return {label, false};
  if (const auto own = evidence(frame)) return {*own, false};
  return {label, true};
}

void StationDialects::note_claim(std::uint8_t s, Label& out, Claim claim) {
  auto& station = station_[s];
  if (claim.weak && station) return;
  if (station && !station->weak && station->dialect != claim.dialect) {
    out.changed_from = station->dialect;
  }
  station = claim;
}

StationDialects::Label StationDialects::label(const Frame& frame, bool check_ok) {
  Label out{frame.dialect, std::nullopt};
  const std::uint8_t s = frame.station;
  if (modbus_family(frame.dialect) && forced_[s]) {
    out.dialect = *forced_[s];
  } else if (choose_ && modbus_family(frame.dialect)) {
    const std::optional<Dialect> own = evidence(frame);
    if (own && check_ok) {
      decided_[s] = *own;
      out.dialect = *own;
    } else if (decided_[s]) {
      out.dialect = *decided_[s];
    } else if (own) {
      out.dialect = *own;
    } else if (frame.role == Role::Response && last_request_[s]) {
      out.dialect = *last_request_[s];
    } else {
      const bool modbus_only =
          fc::is_modbus_function(frame.function) && !fc::is_gsl_function(frame.function);
      out.dialect = modbus_only ? Dialect::Modbus : frame.dialect;
    }
    // GSL names only its own codes; another Modbus function of a GSL station is plain Modbus.
    // (A damaged function code, which no dialect has, keeps the label its bytes were framed by.)
    if (out.dialect == Dialect::Gsl && !fc::is_gsl_function(frame.function) &&
        fc::is_modbus_function(frame.function)) {
      out.dialect = Dialect::Modbus;
    }
    if (frame.role == Role::Request) last_request_[s] = out.dialect;
  }
  if (check_ok) note_claim(s, out, claim_of(frame, out.dialect));
  return out;
}

}  // namespace pvtap::detail
