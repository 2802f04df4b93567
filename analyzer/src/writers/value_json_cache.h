// ValueJsonCache: the register-dependent parts of value objects in jsonl output, rendered once
// per register rather than once per value (a capture repeats the same registers millions of
// times).
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "formatting/json_writer.h"
#include "pvtap/registers/register_decoder.h"

namespace pvtap::analyzer {

class ValueJsonCache {
 public:
  // Writes the whole {"register":...} object of `v`. Inline, so that `w` is not handed on by
  // reference and stays in registers in the caller.
  void write(JsonWriter& w, const DecodedValue& v, Dialect d) { write_to(w.value_out(), v, d); }

 private:
  // The object, where the value goes: what goes before it is placed already.
  void write_to(std::string& out, const DecodedValue& v, Dialect d);
  // Direct-mapped: a slot per key hash, replaced when another register maps to it.
  static constexpr std::size_t kSlots = 1024;  // the hash's top 10 bits
  struct Parts {
    std::uint64_t key = ~std::uint64_t{0};
    const RegisterDef* def = nullptr;
    std::string head;  // {"register":"0x1006","name":"battery voltage","value":
    std::string unit;  // ,"unit":"V"
  };
  const Parts& parts_of(const DecodedValue& v, Dialect d);

  std::array<Parts, kSlots> parts_;
};

}  // namespace pvtap::analyzer
