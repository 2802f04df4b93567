#include "writers/value_json_cache.h"

#include "report/value_json.h"

namespace pvtap::analyzer {

const ValueJsonCache::Parts& ValueJsonCache::parts_of(const DecodedValue& v, Dialect d) {
  const bool hex_address = v.has(ValueWarning::NoWrittenAddress);
  const std::uint64_t key = (std::uint64_t{static_cast<std::uint8_t>(d)} << 32) |
                            (std::uint64_t{hex_address} << 24) | (std::uint64_t{v.address} << 1) |
                            std::uint64_t{v.def != nullptr};
  // Fibonacci hashing spreads neighbouring addresses of different dialects apart.
  Parts& p = parts_[((key + 1) * 0x9E3779B97F4A7C15u) >> 54];
  if (p.key != key || p.def != v.def) {
    p.key = key;
    p.def = v.def;
    p.head.clear();
    p.unit.clear();
    JsonWriter head(p.head);
    write_value_head(head, v, d);
    JsonWriter unit(p.unit);
    write_value_unit(unit, v);
    // Kept with the comma before it: it always follows the value.
    if (!p.unit.empty()) p.unit.insert(0, 1, ',');
  }
  return p;
}

void ValueJsonCache::write_to(std::string& out, const DecodedValue& v, Dialect d) {
  const Parts& p = parts_of(v, d);
  write_kept_value_json(out, p.head, p.unit, v);
}

}  // namespace pvtap::analyzer
