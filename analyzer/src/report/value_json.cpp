#include "report/value_json.h"

#include <array>
#include <iterator>
#include <utility>

#include "pvtap/registers/register_format.h"

namespace pvtap::analyzer {
namespace {

// The value's text; `scratch` is reused so that no string is allocated per
// value once it has grown.
const std::string& value_text(const DecodedValue& v) {
  static thread_local std::string scratch;
  scratch.clear();
  pvtap::append_value_text(scratch, v);
  return scratch;
}

void write_value_text(JsonWriter& w, const DecodedValue& v) {
  w.string(value_text(v));
}

bool has_extra_text(const RegisterDef& def) {
  switch (def.kind) {
    case RegisterKind::Raw:
    case RegisterKind::Enum:
    case RegisterKind::Bits:
    case RegisterKind::BcdPhaseCapacity:
      return true;
    default:
      return false;
  }
}

std::string_view table_key(RegisterTable t) {
  switch (t) {
    case RegisterTable::Holding:
      return "holding";
    case RegisterTable::Input:
      return "input";
    case RegisterTable::Coils:
      return "coils";
    case RegisterTable::DiscreteInputs:
      return "discrete_inputs";
    case RegisterTable::Registers:
      break;
  }
  return "registers";
}

void write_inferred_value(JsonWriter& w, const InferredBlock& b, const InferredValue& v) {
  const auto address = static_cast<std::uint16_t>(b.start + v.offset * address_step(b.dialect));
  w.begin_object();
  w.field("register", inferred_address(b, v));
  w.field("key", unmapped_key(b.table, address).view());
  w.field("type", to_string(v.kind));
  w.field("words", v.words);
  w.key("word_order");
  if (v.words == 2) {
    w.string(v.order == WordOrder::HighFirst ? "high_first" : "low_first");
  } else {
    w.null();
  }
  w.field_bool("constant", v.constant);
  w.field_bool("counter", v.counter);
  w.field_fixed("confidence", v.confidence, 2);
  if (v.kind == InferredKind::Text) {
    w.field("text", v.text);
  } else if (v.kind != InferredKind::Unused) {
    const int decimals = v.kind == InferredKind::Float32 ? 6 : 0;
    w.field_fixed("min", v.min, decimals);
    w.field_fixed("max", v.max, decimals);
    w.field_fixed("last", v.last, decimals);
  }
  w.field("evidence", v.evidence);
  if (!v.hint.empty()) w.field("hint", v.hint);
  w.end_object();
}

}  // namespace

void write_value_head(JsonWriter& w, const DecodedValue& v, Dialect d) {
  w.begin_object();
  w.field("register", format_value_address(v, d).view());
  w.key("name");
  if (v.def == nullptr) {
    w.null();
  } else {
    w.string(v.def->name);
  }
  w.key("value");
}

void write_value_reading(JsonWriter& w, const DecodedValue& v) {
  switch (reading_kind(v)) {
    case ReadingKind::Number:
      append_value_number(w.value_out(), v);
      return;
    case ReadingKind::Text:
      write_value_text(w, v);
      return;
    case ReadingKind::None:
      w.null();
      return;
  }
}

void write_value_unit(JsonWriter& w, const DecodedValue& v) {
  if (v.def == nullptr || v.def->unit.empty()) return;
  w.field("unit", v.def->unit);
}

void write_value_tail(JsonWriter& w, const DecodedValue& v) {
  if (v.def != nullptr && (!v.complete() || has_extra_text(*v.def))) {
    w.key("text");
    write_value_text(w, v);
  }
  if (v.def != nullptr && v.warnings != 0) {
    // The descriptions are constant: quoted once, not escaped again for every value.
    static const auto kQuoted = [] {
      std::array<std::string, std::size(kAllValueWarnings)> quoted;
      for (std::size_t i = 0; i < quoted.size(); ++i) {
        JsonWriter(quoted[i]).string(describe(kAllValueWarnings[i]));
      }
      return quoted;
    }();
    w.key("warnings");
    w.begin_array();
    for (std::size_t i = 0; i < kQuoted.size(); ++i) {
      if (v.has(kAllValueWarnings[i])) w.raw(kQuoted[i]);
    }
    w.end_array();
  }
  w.end_object();
}

void write_value_rest(std::string& out, std::string_view unit_member, const DecodedValue& v) {
  // The reading and the kept unit appended whole; a writer only for what follows the unit.
  switch (reading_kind(v)) {
    case ReadingKind::Number:
      append_value_number(out, v);
      break;
    case ReadingKind::Text:
      JsonWriter(out).string(value_text(v));
      break;
    case ReadingKind::None:
      out += "null";
      break;
  }
  out += unit_member;
  if (v.def != nullptr && (!v.complete() || has_extra_text(*v.def) || v.warnings != 0)) {
    // The head's members are written: the tail's come after a comma.
    JsonWriter w = JsonWriter::more_members(out);
    write_value_tail(w, v);
    return;
  }
  out += '}';
}

void write_value_json(JsonWriter& w, const DecodedValue& v, Dialect d) {
  write_value_head(w, v, d);
  write_value_reading(w, v);
  write_value_unit(w, v);
  write_value_tail(w, v);
}

void write_latest_value_json(JsonWriter& w, const LatestValue& v) {
  if (v.value.def != nullptr) {
    write_value_json(w, v.value, v.dialect);
    return;
  }
  w.begin_object();
  w.field("register", format_value_address(v.value, v.dialect).view());
  w.key("name");
  if (v.coil != nullptr) {
    w.string(v.coil->name);
  } else {
    w.null();
  }
  const std::uint8_t function = table_function(v.table);
  if (function != 0) w.field("function", function);
  w.field_plain("table", table_key(v.table));
  w.field("key", v.coil != nullptr
                     ? v.coil->key
                     : std::string_view(unmapped_key(v.table, v.value.address).view()));
  w.field("value", v.value.raw);
  w.end_object();
}

void write_inferred_block_json(JsonWriter& w, const InferredBlock& b) {
  w.begin_object();
  w.field_plain("table", table_key(b.table));
  w.field("function", b.function);
  w.field("start", format_register_address(b.dialect, b.start).view());
  w.field("count", b.count);
  w.field("replies", b.replies);
  w.key("values");
  w.begin_array();
  for (const InferredValue& v : b.values) write_inferred_value(w, b, v);
  w.end_array();
  w.end_object();
}

}  // namespace pvtap::analyzer
