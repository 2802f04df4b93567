#include "writers/value_json_cache.h"

#include "report/frame_findings.h"

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
    append_value_json_head(p.head, v, d);
    append_value_json_unit(p.unit, v);
  }
  return p;
}

void ValueJsonCache::append(std::string& out, const DecodedValue& v, Dialect d) {
  const Parts& p = parts_of(v, d);
  out += p.head;
  append_value_json_reading(out, v);
  out += p.unit;
  append_value_json_tail(out, v);
}

}  // namespace pvtap::analyzer
