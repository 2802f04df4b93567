// ValueJsonCache: value objects in JSON output rendered once per register and station rather
// than once per value: a capture repeats the same registers millions of times, most of them
// with the reading the station gave last time (alarm words, states, a slowly moving voltage).
#pragma once

#include <array>
#include <bit>
#include <cstdint>
#include <string>

#include "formatting/json_writer.h"
#include "pvtap/registers/register_decoder.h"
#include "report/value_json.h"

namespace pvtap::analyzer {

class ValueJsonCache {
 public:
  // Writes the whole {"register":...} object of `v`, read from `station`. Inline, as is the
  // look-up of a register already seen, so that `w` stays in registers in the caller and a
  // value costs one call; a reading the slot rendered last time is copied, not formatted.
  void write(JsonWriter& w, const DecodedValue& v, Dialect d, std::uint8_t station) {
    Parts& p = parts_of(v, d, station);
    std::string& out = w.value_out();
    if (p.reading.same_as(v)) {
      out += p.whole;
      return;
    }
    render(p, out, v);
  }

 private:
  // Direct-mapped: a slot per key hash, replaced when another register maps to it.
  static constexpr unsigned kSlotBits = 12;
  static constexpr std::size_t kSlots = std::size_t{1} << kSlotBits;

  // Everything the rendering of a value after its head reads, for the kinds whose text
  // follows from these alone (a text register's characters, a BCD's or a device number's
  // parts are not kept: those values are rendered every time).
  struct Reading {
    std::uint64_t value_bits = 0;
    std::uint32_t raw = 0;
    std::uint16_t warnings = 0;
    std::uint8_t scale_decimals = 0;
    std::uint8_t words_present = 0;
    bool kept = false;

    bool same_as(const DecodedValue& v) const {
      return kept && value_bits == std::bit_cast<std::uint64_t>(v.value) && raw == v.raw &&
             warnings == v.warnings && scale_decimals == v.scale_decimals &&
             words_present == v.words_present;
    }
  };
  struct Parts {
    std::uint64_t key = ~std::uint64_t{0};
    const RegisterDef* def = nullptr;
    std::string head;   // {"register":"0x1006","name":"battery voltage","value":
    std::string unit;   // ,"unit":"V"
    Reading reading;    // what `whole` was rendered from
    std::string whole;  // the head, then 52.3,"unit":"V"}: the reading, the unit and the tail
  };
  Parts& parts_of(const DecodedValue& v, Dialect d, std::uint8_t station) {
    const bool hex_address = v.has(ValueWarning::NoWrittenAddress);
    const std::uint64_t key = (std::uint64_t{station} << 40) |
                              (std::uint64_t{static_cast<std::uint8_t>(d)} << 32) |
                              (std::uint64_t{hex_address} << 24) | (std::uint64_t{v.address} << 1) |
                              std::uint64_t{v.def != nullptr};
    // Fibonacci hashing spreads neighbouring addresses of different dialects apart.
    Parts& p = parts_[((key + 1) * 0x9E3779B97F4A7C15u) >> (64 - kSlotBits)];
    if (p.key != key || p.def != v.def) [[unlikely]]
      fill(p, key, v, d);
    return p;
  }
  // Renders the parts of a register not seen before, or not since another took its slot.
  static void fill(Parts& p, std::uint64_t key, const DecodedValue& v, Dialect d);
  // Renders the object into `out`, and keeps it when the value's kind allows.
  static void render(Parts& p, std::string& out, const DecodedValue& v);

  std::array<Parts, kSlots> parts_;
};

}  // namespace pvtap::analyzer
