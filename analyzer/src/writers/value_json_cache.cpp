#include "writers/value_json_cache.h"

#include "report/value_json.h"

namespace pvtap::analyzer {

void ValueJsonCache::fill(Parts& p, std::uint64_t key, const DecodedValue& v, Dialect d) {
  p.key = key;
  p.def = v.def;
  p.head.clear();
  p.unit.clear();
  JsonWriter head(p.head);
  write_value_head(head, v, d);
  // Kept with the comma before it: it always follows the value.
  JsonWriter unit = JsonWriter::more_members(p.unit);
  write_value_unit(unit, v);
}

}  // namespace pvtap::analyzer
