// SunSpec devices: the model chain a master reads from one, learned passively, and the register
// map that chain makes from the published models (protocols/maps/sunspec/models.toml).
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "pvtap/registers/register_map.h"

namespace pvtap {

// Where a SunSpec client looks for the "SunS" marker, in the order it looks.
inline constexpr std::array<std::uint16_t, 3> kSunSpecBases{40000, 50000, 0};
inline constexpr std::uint16_t kSunSpecMarkerHigh = 0x5375;  // "Su"
inline constexpr std::uint16_t kSunSpecMarkerLow = 0x6E53;   // "nS"
inline constexpr std::uint16_t kSunSpecEndModel = 0xFFFF;

// SunSpecModel: one model of a device's chain: its id, its length (L, the registers after the
// two header words) and the address of its ID word.
struct SunSpecModel {
  std::uint16_t id = 0;
  std::uint16_t length = 0;
  std::uint16_t address = 0;
};

// SunSpecChain: the marker's address and the models that follow it, as far as they are known.
struct SunSpecChain {
  static constexpr std::size_t kMaxModels = 64;
  std::uint16_t base = 0;
  std::vector<SunSpecModel> models;
  bool ended = false;  // the end model (0xFFFF) was read: the chain is whole

  // The address of the next model's ID word.
  std::uint32_t next_header() const {
    return models.empty() ? base + 2u : models.back().address + 2u + models.back().length;
  }
  // Appends a model at next_header(); false when the chain is full or runs past 0xFFFF.
  bool append(std::uint16_t id, std::uint16_t length);
};

// The published name of a model ("inverter (three phase)"); empty when pvtap does not know it.
std::string_view sunspec_model_name(std::uint16_t id);

// The register map of a chain: the marker, each model's ID and L, and the points of every
// model pvtap knows, at their addresses, with keys "m103_w" ("m160_2_dcv" for the second
// module of a repeating group, "m160x2_..." for a model's second instance in the chain).
RegisterMapResult sunspec_register_map(const SunSpecChain& chain, std::string_view source_name);

// SunSpecLearner: a station's chain, learned from the read replies a master gets: the marker
// at one of kSunSpecBases, then each header in turn as some read covers it.
class SunSpecLearner {
 public:
  // Learns from a reply's words read at `start`; true when the chain grew.
  bool learn(std::uint16_t start, std::span<const std::uint16_t> words);
  bool found() const { return found_; }
  const SunSpecChain& chain() const { return chain_; }

 private:
  bool find_marker(std::uint16_t start, std::span<const std::uint16_t> words);

  SunSpecChain chain_;
  bool found_ = false;
  bool stopped_ = false;  // the chain ended, or cannot go on
};

// SunSpecStations: what a decoder has learned of each station: its chain, the maps the chain
// made (every version is kept: values decoded earlier point into them), and the last value of
// each scale factor register read.
class SunSpecStations {
 public:
  static constexpr std::size_t kMaxVersions = 64;  // per station; a chain has few models

  const RegisterMap* map(std::uint8_t station) const {
    const Station* s = stations_[station].get();
    return s != nullptr && !s->versions.empty() ? &s->versions.back() : nullptr;
  }
  const SunSpecChain* chain(std::uint8_t station) const {
    const Station* s = stations_[station].get();
    return s != nullptr && s->learner.found() ? &s->learner.chain() : nullptr;
  }
  // Feeds a read reply's words; builds the station's map anew when its chain grew.
  void learn(std::uint8_t station, std::uint16_t start, std::span<const std::uint16_t> words);
  void remember_scale_factor(std::uint8_t station, std::uint16_t address, std::int16_t value);
  // The last value of a scale factor register of the station; false when none was read.
  bool scale_factor(std::uint8_t station, std::uint16_t address, std::int16_t& value) const;
  void clear();

 private:
  struct Station {
    SunSpecLearner learner;
    std::deque<RegisterMap> versions;
    std::vector<std::pair<std::uint16_t, std::int16_t>> scale_factors;  // by address
  };
  Station& station(std::uint8_t s);

  std::array<std::unique_ptr<Station>, 256> stations_;
};

}  // namespace pvtap
