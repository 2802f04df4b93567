// RegisterImage: the words an inverter holds, filled by key through the core's register map
// of its dialect, read back as the blocks a master asks for.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "bus/bus_event.h"
#include "pvtap/codec/frame.h"
#include "pvtap/registers/register_map.h"

namespace pvtap::sim {

class RegisterImage {
 public:
  explicit RegisterImage(Dialect dialect);

  // Stores a physical value (volts, kWh ...) as the map's scaled raw words.
  void set_value(std::string_view key, double value);
  // Stores raw bits (bit tables, BCD, enums, text words) as they are.
  void set_raw(std::string_view key, std::uint32_t raw);
  void set_text(std::string_view key, std::string_view text);

  // `count` consecutive words from a written start address (ASCII steps by 2).
  WordList block(std::uint16_t start, std::uint16_t count) const;
  // What each register of that block held, for the ground truth.
  std::vector<RegisterTruth> truth(std::uint16_t start, std::uint16_t count) const;

 private:
  const RegisterDef& def(std::string_view key) const;
  void put_words(const RegisterDef& d, std::uint32_t raw);
  std::uint16_t word_at(std::uint16_t address) const;
  std::string text_of(const RegisterDef& d) const;

  Dialect dialect_;
  const RegisterMap* map_;
  std::map<std::uint16_t, std::uint16_t> words_;  // written address -> word
};

}  // namespace pvtap::sim
