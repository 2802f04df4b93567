#include "diff/register_ranges.h"

#include <algorithm>
#include <optional>

#include "report/frame_findings.h"

namespace pvtap::analyzer {
namespace {

// The reading as a number where it is one (ReadingKind::Number): the scaled value of numbers
// and BCD, the raw word of enums, bits and words outside the map; nullopt for texts and
// readings that are incomplete or not finite.
std::optional<double> reading_number(const DecodedValue& v) {
  if (reading_kind(v) != ReadingKind::Number) return std::nullopt;
  if (v.def == nullptr) return static_cast<double>(v.raw);
  switch (v.def->kind) {
    case RegisterKind::Number:
    case RegisterKind::Bcd:
    case RegisterKind::BcdPhaseCapacity:
      return v.value;
    default:
      return static_cast<double>(v.raw);
  }
}

}  // namespace

void RegisterRanges::frame(const EventContext& c, const SessionFrame& f) {
  if (!f.values_trusted || !f.station || f.values.empty()) return;
  for (const DecodedValue& v : f.values) {
    const std::optional<double> number = reading_number(v);
    if (!number) continue;
    const RegisterKey key{std::string(c.bus), *f.station, f.dialect, v.address};
    auto [it, added] = ranges_.try_emplace(key);
    ValueRange& range = it->second;
    if (added) {
      range.min = range.max = *number;
      range.name = v.name();
      range.unit = v.unit();
    }
    range.min = std::min(range.min, *number);
    range.max = std::max(range.max, *number);
    ++range.readings;
  }
}

}  // namespace pvtap::analyzer
