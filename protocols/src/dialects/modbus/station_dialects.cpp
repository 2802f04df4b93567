#include "dialects/modbus/station_dialects.h"

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
      undecided_(enabled.prefers_modbus() ? Dialect::Modbus : Dialect::Gsl),
      gsl_runs_(wire_runs(decoder.map(Dialect::Gsl), decoder.options())) {
  for (std::size_t s = 0; s < stations_.size(); ++s) {
    const RegisterMap* own = decoder.station_map(static_cast<std::uint8_t>(s));
    if (own != nullptr && modbus_family(own->dialect())) {
      stations_[s].forced = static_cast<std::uint8_t>(own->dialect());
    }
  }
}

// Every register asked for is one the GSL map has. Overlapping it is not enough: a meter
// reading 1024..1039 is not a KSTAR inverter because 1030..1033 are its alarm words.
bool StationDialects::addresses_gsl_map(std::uint16_t start, std::uint16_t count) {
  const std::uint32_t range = (std::uint32_t{start} << 16) | count;
  RangeMemo& m = memo_[(start ^ (start >> 4) ^ count) % kMemoSize];
  if (!m.known || m.range != range) m = RangeMemo{range, true, search_gsl_map(start, count)};
  return m.gsl;
}

bool StationDialects::search_gsl_map(std::uint16_t start, std::uint16_t count) const {
  const unsigned last = unsigned{start} + std::max<unsigned>(count, 1) - 1;
  const auto after = std::upper_bound(gsl_runs_.begin(), gsl_runs_.end(), start,
                                      [](std::uint16_t a, const Run& r) { return a < r.first; });
  if (after == gsl_runs_.begin()) return false;
  const Run& run = *std::prev(after);
  return start >= run.first && last <= run.last;
}

// What a frame says of its station by itself: only a request naming registers says anything.
std::optional<Dialect> StationDialects::evidence(const Frame& f) {
  if (f.role != Role::Request || !addresses_registers(f.function) || !f.start) {
    return std::nullopt;
  }
  const std::uint16_t count = f.count.value_or(1);
  return addresses_gsl_map(*f.start, count) ? Dialect::Gsl : Dialect::Modbus;
}

Dialect StationDialects::choose(const Frame& frame, Station& st, std::optional<Dialect> own,
                                bool check_ok) {
  Dialect d = frame.dialect;
  if (own && check_ok) {
    st.decided = static_cast<std::uint8_t>(*own);
    d = *own;
  } else if (st.decided != kNone) {
    d = static_cast<Dialect>(st.decided);
  } else if (own) {
    d = *own;
  } else if (frame.role == Role::Response && st.last_request != kNone) {
    d = static_cast<Dialect>(st.last_request);
  } else if (fc::is_modbus_function(frame.function) && !fc::is_gsl_function(frame.function)) {
    d = Dialect::Modbus;
  } else if (d == Dialect::Gsl) {
    d = undecided_;
  }
  d = own_codes_only(d, frame.function, check_ok);
  if (frame.role == Role::Request) st.last_request = static_cast<std::uint8_t>(d);
  return d;
}

// A station's first frame claims weakly: a later claim replaces it without a change being
// reported (a logger probing a GSL inverter with 0x2B first).
void StationDialects::note_claim(Station& st, Label& out, Dialect claim, bool weak) {
  const auto code = static_cast<std::uint8_t>(claim);
  if (st.speaks == kNone || (st.speaks_weakly && !weak)) {
    st.speaks = code;
    st.speaks_weakly = weak;
    return;
  }
  if (weak || st.speaks == code) return;
  if (!st.speaks_weakly) out.changed_from = static_cast<Dialect>(st.speaks);
  st.speaks = code;
  st.speaks_weakly = false;
}

// A frame of a dialect of its own says which its station speaks; a GSL/Modbus frame only
// when its registers say it (or weakly, as a station's first frame). A bad frame claims
// nothing.
StationDialects::Label StationDialects::label_in_full(const Frame& frame, bool check_ok) {
  Label out{frame.dialect, std::nullopt};
  Station& st = stations_[frame.station];
  if (!modbus_family(frame.dialect)) {
    if (check_ok) note_claim(st, out, frame.dialect, false);
    return out;
  }
  if (st.forced != kNone) {
    out.dialect = static_cast<Dialect>(st.forced);
    if (check_ok) note_claim(st, out, out.dialect, false);
    return out;
  }
  // What the frame's own registers say, once: it labels the frame and judges its station.
  const std::optional<Dialect> own = evidence(frame);
  if (choose_) out.dialect = choose(frame, st, own, check_ok);
  if (check_ok) note_claim(st, out, own.value_or(out.dialect), !own);
  return out;
}

}  // namespace pvtap::detail
