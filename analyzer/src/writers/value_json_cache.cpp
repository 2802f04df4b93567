#include "writers/value_json_cache.h"

#include "report/value_json.h"

namespace pvtap::analyzer {
namespace {

// Kinds whose text is a function of the value, the raw words, the warnings and the decimals,
// all of which Reading compares.
bool rendering_kept(const RegisterDef* def) {
  if (def == nullptr) return true;  // the word in hex
  switch (def->kind) {
    case RegisterKind::Number:
    case RegisterKind::Raw:
    case RegisterKind::Enum:
    case RegisterKind::Bits:
      return true;
    default:
      return false;
  }
}

}  // namespace

void ValueJsonCache::fill(Parts& p, std::uint64_t key, const DecodedValue& v, Dialect d) {
  p.key = key;
  p.def = v.def;
  p.head.clear();
  p.unit.clear();
  p.reading.kept = false;
  JsonWriter head(p.head);
  write_value_head(head, v, d);
  // Kept with the comma before it: it always follows the value.
  JsonWriter unit = JsonWriter::more_members(p.unit);
  write_value_unit(unit, v);
}

void ValueJsonCache::render(Parts& p, std::string& out, const DecodedValue& v) {
  const std::size_t at = out.size();
  out += p.head;
  write_value_rest(out, p.unit, v);
  p.reading.kept = rendering_kept(v.def);
  if (!p.reading.kept) return;
  p.reading.value_bits = std::bit_cast<std::uint64_t>(v.value);
  p.reading.raw = v.raw;
  p.reading.warnings = v.warnings;
  p.reading.scale_decimals = v.scale_decimals;
  p.reading.words_present = v.words_present;
  p.whole.assign(out, at);
}

}  // namespace pvtap::analyzer
