// The storage behind a RegisterMap (private to the core).
#pragma once

#include <cstdint>
#include <deque>
#include <string>
#include <vector>

#include "pvtap/registers/register_map.h"

namespace pvtap {

// One covered address: which entry covers it and which word of which instance it is.
struct RegisterSlotEntry {
  std::uint16_t address = 0;
  std::uint16_t def_index = 0;
  std::uint16_t word = 0;
  std::uint16_t instance = 0;
};

// Built once and never changed, so the string views of the entries stay valid; the deque
// keeps every interned string where it was put.
struct RegisterMap::Data {
  Dialect dialect = kDefaultDialect;
  std::uint16_t step = 1;  // address_step(dialect), which locate() needs for every register
  MapMode mode = MapMode::Replace;
  std::string title;
  std::string source_name;
  std::deque<std::string> strings;
  std::vector<EnumText> enum_texts;
  std::vector<BitName> bit_names;
  std::vector<RegisterDef> defs;         // sorted by address
  std::vector<RegisterSlotEntry> slots;  // sorted by address, one per covered address
  std::vector<CoilDef> coils;            // sorted by address
  std::vector<CoilDef> discrete_inputs;  // sorted by address
  bool has_scale_factors = false;
  // slots' index by address, from slots.front().address on (kNoSlot where none covers it):
  // every register of every reply is looked up, so the lookup is one load, not a search.
  static constexpr std::uint32_t kNoSlot = 0xFFFFFFFF;
  std::uint16_t first_address = 0;
  std::vector<std::uint32_t> slot_by_address;
};

}  // namespace pvtap
