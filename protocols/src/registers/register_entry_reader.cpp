#include "registers/register_entry_reader.h"

namespace pvtap::detail {

RegisterSpec RegisterEntryReader::read(const toml::table& table) {
  RegisterSpec spec;
  spec.line = line_of(table.source());
  spec.column = column_of(table.source());
  PendingFields pending;
  for (const auto& [key, node] : table) read_field(key, node, spec, pending);
  if (!pending.has_address) nodes_.fail(table.source(), "register entry has no address");
  if (!pending.has_kind) spec.kind = inferred_kind(spec);
  if (spec.float32 && !pending.has_words) spec.words = 2;  // a float32 is two words wide
  if (pending.last) apply_last(spec, pending);
  return spec;
}

RegisterKind RegisterEntryReader::inferred_kind(const RegisterSpec& spec) {
  if (!spec.values.empty()) return RegisterKind::Enum;
  if (!spec.bits.empty()) return RegisterKind::Bits;
  return RegisterKind::Number;
}

void RegisterEntryReader::apply_last(RegisterSpec& spec, const PendingFields& pending) {
  const std::int64_t step = address_step(dialect_);
  const std::int64_t span = *pending.last - spec.address;
  if (span < 0 || span % step != 0) {
    nodes_.fail_at(pending.last_line, pending.last_column,
                   "'last' must be at or after 'address'" +
                       std::string(step > 1 ? ", an even number of addresses on" : ""));
    return;
  }
  spec.repeat = span / step + 1;
}

void RegisterEntryReader::read_field(const toml::key& key, const toml::node& node,
                                     RegisterSpec& spec, PendingFields& pending) {
  const std::string_view name = key.str();
  if (name == "address") {
    pending.has_address = true;
    if (const auto* i = nodes_.expect_integer(node, "address")) spec.address = i->get();
  } else if (name == "last") {
    pending.last_line = line_of(node.source());
    pending.last_column = column_of(node.source());
    if (const auto* i = nodes_.expect_integer(node, "last")) pending.last = i->get();
  } else if (name == "key" || name == "name" || name == "unit" || name == "scale_factor") {
    if (const auto* s = nodes_.expect_string(node, name)) {
      (name == "key"    ? spec.key
       : name == "name" ? spec.name
       : name == "unit" ? spec.unit
                        : spec.scale_factor) = s->get();
    }
  } else if (name == "kind") {
    pending.has_kind = true;
    read_kind(node, spec);
  } else if (name == "no_value") {
    if (const auto* i = nodes_.expect_integer(node, "no_value")) spec.no_value = i->get();
  } else if (name == "words" || name == "decimals") {
    if (const auto* i = nodes_.expect_integer(node, name)) {
      pending.has_words = pending.has_words || name == "words";
      if (name == "words")
        spec.words = i->get();
      else
        spec.decimals = i->get();
    }
  } else {
    read_option_field(key, node, spec);
  }
}

void RegisterEntryReader::read_option_field(const toml::key& key, const toml::node& node,
                                            RegisterSpec& spec) {
  const std::string_view name = key.str();
  if (name == "scale") {
    read_scale(node, spec);
  } else if (name == "signed") {
    if (const auto* b = node.as_boolean())
      spec.is_signed = b->get();
    else
      nodes_.fail(node.source(), "signed must be true or false");
  } else if (name == "combine") {
    read_combine(node, spec);
  } else if (name == "word_order") {
    read_word_order(node, spec);
  } else if (name == "values") {
    read_values(node, spec);
  } else if (name == "bits") {
    if (const auto* t = node.as_table())
      spec.bits = nodes_.read_number_table(*t, "bit");
    else
      nodes_.fail(node.source(), "bits must be a table: [register.bits] 0 = \"name\"");
  } else {
    nodes_.fail(key.source(),
                "unknown register field '" + std::string(name) +
                    "' (expected address, last, key, name, kind, scale, unit, words, "
                    "combine, word_order, signed, decimals, values, bits, scale_factor, "
                    "no_value)");
  }
}

void RegisterEntryReader::read_kind(const toml::node& node, RegisterSpec& spec) {
  const auto* s = nodes_.expect_string(node, "kind");
  if (s == nullptr) return;
  if (s->get() == "float32") {
    spec.kind = RegisterKind::Number;
    spec.float32 = true;
  } else if (auto kind = register_kind_from_string(s->get())) {
    spec.kind = *kind;
  } else {
    nodes_.fail(node.source(), "unknown kind '" + s->get() +
                                   "' (expected number, float32, raw, enum, bits, text, bcd, "
                                   "bcd_phase_capacity, bcd_year_month or device_number)");
  }
}

void RegisterEntryReader::read_word_order(const toml::node& node, RegisterSpec& spec) {
  const auto* s = nodes_.expect_string(node, "word_order");
  if (s == nullptr) return;
  if (s->get() == "high_first") {
    spec.word_order = WordOrder::HighFirst;
  } else if (s->get() == "low_first") {
    spec.word_order = WordOrder::LowFirst;
  } else {
    nodes_.fail(node.source(),
                "unknown word order '" + s->get() + "' (expected high_first or low_first)");
  }
}

void RegisterEntryReader::read_scale(const toml::node& node, RegisterSpec& spec) {
  if (const auto* f = node.as_floating_point()) {
    spec.scale = f->get();
  } else if (const auto* i = node.as_integer()) {
    spec.scale = static_cast<double>(i->get());
  } else {
    nodes_.fail(node.source(), "scale must be a number");
  }
}

void RegisterEntryReader::read_combine(const toml::node& node, RegisterSpec& spec) {
  const auto* s = nodes_.expect_string(node, "combine");
  if (s == nullptr) return;
  if (s->get() == "binary") {
    spec.pair_rule = PairRule::Binary;
  } else if (s->get() == "decimal") {
    spec.pair_rule = PairRule::Decimal;
  } else if (s->get() == "option") {
    spec.pair_rule = PairRule::FromOptions;
  } else {
    nodes_.fail(node.source(),
                "unknown combine rule '" + s->get() + "' (expected binary, decimal or option)");
  }
}

void RegisterEntryReader::read_values(const toml::node& node, RegisterSpec& spec) {
  if (const auto* t = node.as_table()) {
    spec.values = nodes_.read_number_table(*t, "value");
  } else if (const auto* s = node.as_string()) {
    auto it = enums_.find(s->get());
    if (it != enums_.end())
      spec.values = it->second;
    else
      nodes_.fail(node.source(), "no enum named '" + s->get() + "' in [enums]");
  } else {
    nodes_.fail(node.source(),
                "values must be a table { 0 = \"off\" } or the name of an [enums] table");
  }
}

CoilSpec read_coil_entry(MapNodeReader& nodes, const toml::table& table, CoilTable kind) {
  CoilSpec spec;
  spec.table = kind;
  spec.line = line_of(table.source());
  spec.column = column_of(table.source());
  bool has_address = false;
  for (const auto& [key, node] : table) {
    const std::string_view name = key.str();
    if (name == "address") {
      has_address = true;
      if (const auto* i = nodes.expect_integer(node, "address")) spec.address = i->get();
    } else if (name == "key" || name == "name") {
      if (const auto* s = nodes.expect_string(node, name)) {
        (name == "key" ? spec.key : spec.name) = s->get();
      }
    } else {
      nodes.fail(key.source(), "unknown " + std::string(coil_table_name(kind)) + " field '" +
                                   std::string(name) + "' (expected address, key, name)");
    }
  }
  if (!has_address) {
    nodes.fail(table.source(), std::string(coil_table_name(kind)) + " entry has no address");
  }
  return spec;
}

}  // namespace pvtap::detail
