// ValueJsonCache: the register-dependent parts of value objects in jsonl output, rendered once
// per register rather than once per value (a capture repeats the same registers millions of
// times).
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "formatting/json_writer.h"
#include "pvtap/registers/register_decoder.h"
#include "report/value_json.h"

namespace pvtap::analyzer {

class ValueJsonCache {
 public:
  // Writes the whole {"register":...} object of `v`. Inline, as is the look-up of a register
  // already seen, so that `w` stays in registers in the caller and a value costs one call.
  void write(JsonWriter& w, const DecodedValue& v, Dialect d) {
    const Parts& p = parts_of(v, d);
    write_kept_value_json(w.value_out(), p.head, p.unit, v);
  }

 private:
  // Direct-mapped: a slot per key hash, replaced when another register maps to it.
  static constexpr std::size_t kSlots = 1024;  // the hash's top 10 bits
  struct Parts {
    std::uint64_t key = ~std::uint64_t{0};
    const RegisterDef* def = nullptr;
    std::string head;  // {"register":"0x1006","name":"battery voltage","value":
    std::string unit;  // ,"unit":"V"
  };
  const Parts& parts_of(const DecodedValue& v, Dialect d) {
    const bool hex_address = v.has(ValueWarning::NoWrittenAddress);
    const std::uint64_t key = (std::uint64_t{static_cast<std::uint8_t>(d)} << 32) |
                              (std::uint64_t{hex_address} << 24) | (std::uint64_t{v.address} << 1) |
                              std::uint64_t{v.def != nullptr};
    // Fibonacci hashing spreads neighbouring addresses of different dialects apart.
    Parts& p = parts_[((key + 1) * 0x9E3779B97F4A7C15u) >> 54];
    if (p.key != key || p.def != v.def) [[unlikely]]
      fill(p, key, v, d);
    return p;
  }
  // Renders the parts of a register not seen before, or not since another took its slot.
  static void fill(Parts& p, std::uint64_t key, const DecodedValue& v, Dialect d);

  std::array<Parts, kSlots> parts_;
};

}  // namespace pvtap::analyzer
