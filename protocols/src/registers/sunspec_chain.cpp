// A SunSpec station's chain learned from the reads its master makes, and what was learned of
// each station.
#include <algorithm>

#include "pvtap/registers/sunspec.h"

namespace pvtap {
namespace {

// The marker's two words at one of the bases a client scans, inside a read at `start`.
std::optional<std::uint16_t> marker_base(std::uint16_t start,
                                         std::span<const std::uint16_t> words) {
  for (const std::uint16_t base : kSunSpecBases) {
    if (base < start) continue;
    const std::size_t at = base - start;
    if (at + 1 < words.size() && words[at] == kSunSpecMarkerHigh &&
        words[at + 1] == kSunSpecMarkerLow) {
      return base;
    }
  }
  return std::nullopt;
}

}  // namespace

bool SunSpecChain::append(std::uint16_t id, std::uint16_t length) {
  const std::uint32_t at = next_header();
  if (models.size() >= kMaxModels || at + 2u + length > 0xFFFFu) return false;
  models.push_back(SunSpecModel{id, length, static_cast<std::uint16_t>(at)});
  return true;
}

bool SunSpecLearner::find_marker(std::uint16_t start, std::span<const std::uint16_t> words) {
  const std::optional<std::uint16_t> base = marker_base(start, words);
  if (!base) return false;
  chain_.base = *base;
  found_ = true;
  return true;
}

bool SunSpecLearner::learn(std::uint16_t start, std::span<const std::uint16_t> words) {
  if (stopped_) return false;
  bool grew = false;
  if (!found_) {
    if (!find_marker(start, words)) return false;
    grew = true;
  }
  // One read may cover several headers: a client that reads a whole model with the header
  // after it, or the scan of a device that answers long reads.
  for (;;) {
    const std::uint32_t at = chain_.next_header();
    if (at < start || at + 1u >= std::uint32_t{start} + words.size()) break;
    const std::uint16_t id = words[at - start];
    const std::uint16_t length = words[at + 1u - start];
    if (id == kSunSpecEndModel) {
      chain_.ended = true;
      stopped_ = true;
      return true;
    }
    if (!chain_.append(id, length)) {
      stopped_ = true;
      break;
    }
    grew = true;
  }
  return grew;
}

SunSpecStations::Station& SunSpecStations::station(std::uint8_t s) {
  if (!stations_[s]) stations_[s] = std::make_unique<Station>();
  return *stations_[s];
}

void SunSpecStations::learn(std::uint8_t s, std::uint16_t start,
                            std::span<const std::uint16_t> words) {
  // Most stations are not SunSpec devices: nothing is kept for one until it shows the marker.
  if (!stations_[s] && !marker_base(start, words)) return;
  Station& st = station(s);
  if (!st.learner.learn(start, words) || st.versions.size() >= kMaxVersions) return;
  RegisterMapResult map = sunspec_register_map(
      st.learner.chain(), "SunSpec chain of station " + std::to_string(unsigned{s}));
  if (map) st.versions.push_back(map.value());
}

void SunSpecStations::remember_scale_factor(std::uint8_t s, std::uint16_t address,
                                            std::int16_t value) {
  auto& known = station(s).scale_factors;
  for (auto& [at, v] : known) {
    if (at == address) {
      v = value;
      return;
    }
  }
  known.emplace_back(address, value);
}

bool SunSpecStations::scale_factor(std::uint8_t s, std::uint16_t address,
                                   std::int16_t& value) const {
  const Station* st = stations_[s].get();
  if (st == nullptr) return false;
  for (const auto& [at, v] : st->scale_factors) {
    if (at == address) {
      value = v;
      return true;
    }
  }
  return false;
}

void SunSpecStations::clear() {
  for (auto& s : stations_) s.reset();
}

}  // namespace pvtap
