// Reads the TOML form of a register map into entry specs; the builder checks the rest.
#include <toml++/toml.h>
#include <charconv>
#include <map>

#include "pvtap/registers/register_map.h"
#include "registers/map_diagnostics.h"
#include "registers/register_map_builder.h"

namespace pvtap {
namespace {

using detail::RegisterSpec;
using detail::SpecValue;

std::uint32_t line_of(const toml::source_region& r) {
  return r.begin.line;
}
std::uint32_t column_of(const toml::source_region& r) {
  return r.begin.column;
}

// "12" or "0x1F": the keys of value and bit tables.
std::optional<std::int64_t> parse_number_key(std::string_view text) {
  int base = 10;
  if (text.size() > 2 && text[0] == '0' && (text[1] == 'x' || text[1] == 'X')) {
    text.remove_prefix(2);
    base = 16;
  }
  std::int64_t value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value, base);
  if (ec != std::errc() || end != text.data() + text.size() || text.empty()) return std::nullopt;
  return value;
}

std::optional<Dialect> dialect_from_string(std::string_view text) {
  for (Dialect d : {Dialect::Ascii, Dialect::Hybrid, Dialect::Gsl}) {
    if (to_string(d) == text) return d;
  }
  return std::nullopt;
}

// Fields of a [[register]] table still to be combined after all have been read.
struct PendingFields {
  std::optional<std::int64_t> last;
  bool has_address = false;
  bool has_kind = false;
  std::uint32_t last_line = 0;
  std::uint32_t last_column = 0;
};

class MapFileReader {
 public:
  explicit MapFileReader(std::string_view source) { problems_.source = std::string(source); }

  RegisterMapResult read(const toml::table& root) {
    detail::MapHeaderSpec header = read_header(root);
    if (!dialect_known_) return RegisterMapResult::failure(std::move(problems_.items));
    read_enums(root.get("enums"));
    RegisterMapBuilder builder(std::move(header));
    read_registers(root.get("register"), builder);
    return std::move(builder).build(std::move(problems_.items));
  }

 private:
  void fail(const toml::source_region& where, std::string message) {
    problems_.add(line_of(where), column_of(where), std::move(message));
  }

  const toml::value<std::string>* expect_string(const toml::node& node, std::string_view what) {
    const auto* s = node.as_string();
    if (s == nullptr) fail(node.source(), std::string(what) + " must be a string");
    return s;
  }

  const toml::value<std::int64_t>* expect_integer(const toml::node& node, std::string_view what) {
    const auto* i = node.as_integer();
    if (i == nullptr) fail(node.source(), std::string(what) + " must be an integer");
    return i;
  }

  detail::MapHeaderSpec read_header(const toml::table& root) {
    detail::MapHeaderSpec header;
    header.source_name = problems_.source;
    for (const auto& [key, node] : root) {
      const std::string_view name = key.str();
      if (name == "dialect") {
        read_dialect(node, header);
      } else if (name == "title") {
        if (const auto* s = expect_string(node, "title")) header.title = s->get();
      } else if (name == "mode") {
        read_mode(node, header);
      } else if (name != "enums" && name != "register") {
        fail(key.source(), "unknown setting '" + std::string(name) +
                               "' (expected dialect, title, mode, [enums] or [[register]])");
      }
    }
    if (!root.contains("dialect")) {
      problems_.add(1, 1,
                    "the map must name its dialect: dialect = \"ascii\", \"hybrid\" or \"gsl\"");
    }
    return header;
  }

  void read_dialect(const toml::node& node, detail::MapHeaderSpec& header) {
    const auto* s = expect_string(node, "dialect");
    if (s == nullptr) return;
    if (auto d = dialect_from_string(s->get())) {
      header.dialect = *d;
      dialect_ = *d;
      dialect_known_ = true;
    } else {
      fail(node.source(), "unknown dialect '" + s->get() + "' (expected ascii, hybrid or gsl)");
    }
  }

  void read_mode(const toml::node& node, detail::MapHeaderSpec& header) {
    const auto* s = expect_string(node, "mode");
    if (s == nullptr) return;
    if (s->get() == "replace") {
      header.mode = MapMode::Replace;
    } else if (s->get() == "extend") {
      header.mode = MapMode::Extend;
    } else {
      fail(node.source(), "unknown mode '" + s->get() + "' (expected replace or extend)");
    }
  }

  void read_enums(const toml::node* node) {
    if (node == nullptr) return;
    const auto* table = node->as_table();
    if (table == nullptr) {
      fail(node->source(), "[enums] must be a table of value tables");
      return;
    }
    for (const auto& [key, entry] : *table) {
      if (const auto* values = entry.as_table()) {
        enums_[std::string(key.str())] = read_number_table(*values, "value");
      } else {
        fail(key.source(), "enum '" + std::string(key.str()) + "' must be a table of values");
      }
    }
  }

  // A table whose keys are numbers ("3" or "0x5555") and whose values are texts.
  std::vector<SpecValue> read_number_table(const toml::table& table, std::string_view what) {
    std::vector<SpecValue> out;
    for (const auto& [key, node] : table) {
      const auto number = parse_number_key(key.str());
      if (!number) {
        fail(key.source(), std::string(what) + " '" + std::string(key.str()) +
                               "' is not a number (write 3 or 0x1F)");
        continue;
      }
      const auto* text = expect_string(node, std::string(what) + " text");
      if (text == nullptr) continue;
      out.push_back(
          SpecValue{*number, text->get(), line_of(key.source()), column_of(key.source())});
    }
    return out;
  }

  void read_registers(const toml::node* node, RegisterMapBuilder& builder) {
    if (node == nullptr) return;
    const auto* entries = node->as_array();
    if (entries == nullptr) {
      fail(node->source(), "registers are written as [[register]] (an array of tables)");
      return;
    }
    for (const toml::node& entry : *entries) {
      const auto* table = entry.as_table();
      if (table == nullptr) {
        fail(entry.source(), "each [[register]] entry must be a table");
        continue;
      }
      builder.add(read_register(*table));
    }
  }

  RegisterSpec read_register(const toml::table& table) {
    RegisterSpec spec;
    spec.line = line_of(table.source());
    spec.column = column_of(table.source());
    PendingFields pending;
    for (const auto& [key, node] : table) read_field(key, node, spec, pending);
    if (!pending.has_address) fail(table.source(), "register entry has no address");
    if (!pending.has_kind) spec.kind = inferred_kind(spec);
    if (pending.last) apply_last(spec, pending);
    return spec;
  }

  static RegisterKind inferred_kind(const RegisterSpec& spec) {
    if (!spec.values.empty()) return RegisterKind::Enum;
    if (!spec.bits.empty()) return RegisterKind::Bits;
    return RegisterKind::Number;
  }

  void apply_last(RegisterSpec& spec, const PendingFields& pending) {
    const std::int64_t step = address_step(dialect_);
    const std::int64_t span = *pending.last - spec.address;
    if (span < 0 || span % step != 0) {
      problems_.add(pending.last_line, pending.last_column,
                    "'last' must be at or after 'address'" +
                        std::string(step > 1 ? ", an even number of addresses on" : ""));
      return;
    }
    spec.repeat = span / step + 1;
  }

  void read_field(const toml::key& key, const toml::node& node, RegisterSpec& spec,
                  PendingFields& pending) {
    const std::string_view name = key.str();
    if (name == "address") {
      pending.has_address = true;
      if (const auto* i = expect_integer(node, "address")) spec.address = i->get();
    } else if (name == "last") {
      pending.last_line = line_of(node.source());
      pending.last_column = column_of(node.source());
      if (const auto* i = expect_integer(node, "last")) pending.last = i->get();
    } else if (name == "key" || name == "name" || name == "unit") {
      if (const auto* s = expect_string(node, name)) {
        (name == "key" ? spec.key : name == "name" ? spec.name : spec.unit) = s->get();
      }
    } else if (name == "kind") {
      pending.has_kind = true;
      read_kind(node, spec);
    } else if (name == "words" || name == "decimals") {
      if (const auto* i = expect_integer(node, name)) {
        if (name == "words")
          spec.words = i->get();
        else
          spec.decimals = i->get();
      }
    } else {
      read_option_field(key, node, spec);
    }
  }

  void read_option_field(const toml::key& key, const toml::node& node, RegisterSpec& spec) {
    const std::string_view name = key.str();
    if (name == "scale") {
      read_scale(node, spec);
    } else if (name == "signed") {
      if (const auto* b = node.as_boolean())
        spec.is_signed = b->get();
      else
        fail(node.source(), "signed must be true or false");
    } else if (name == "combine") {
      read_combine(node, spec);
    } else if (name == "values") {
      read_values(node, spec);
    } else if (name == "bits") {
      if (const auto* t = node.as_table())
        spec.bits = read_number_table(*t, "bit");
      else
        fail(node.source(), "bits must be a table: [register.bits] 0 = \"name\"");
    } else {
      fail(key.source(), "unknown register field '" + std::string(name) +
                             "' (expected address, last, key, name, kind, scale, unit, words, "
                             "combine, signed, decimals, values, bits)");
    }
  }

  void read_kind(const toml::node& node, RegisterSpec& spec) {
    const auto* s = expect_string(node, "kind");
    if (s == nullptr) return;
    if (auto kind = register_kind_from_string(s->get())) {
      spec.kind = *kind;
    } else {
      fail(node.source(), "unknown kind '" + s->get() +
                              "' (expected number, raw, enum, bits, text, bcd, "
                              "bcd_phase_capacity, bcd_year_month or device_number)");
    }
  }

  void read_scale(const toml::node& node, RegisterSpec& spec) {
    if (const auto* f = node.as_floating_point()) {
      spec.scale = f->get();
    } else if (const auto* i = node.as_integer()) {
      spec.scale = static_cast<double>(i->get());
    } else {
      fail(node.source(), "scale must be a number");
    }
  }

  void read_combine(const toml::node& node, RegisterSpec& spec) {
    const auto* s = expect_string(node, "combine");
    if (s == nullptr) return;
    if (s->get() == "binary") {
      spec.pair_rule = PairRule::Binary;
    } else if (s->get() == "decimal") {
      spec.pair_rule = PairRule::Decimal;
    } else if (s->get() == "option") {
      spec.pair_rule = PairRule::FromOptions;
    } else {
      fail(node.source(),
           "unknown combine rule '" + s->get() + "' (expected binary, decimal or option)");
    }
  }

  void read_values(const toml::node& node, RegisterSpec& spec) {
    if (const auto* t = node.as_table()) {
      spec.values = read_number_table(*t, "value");
    } else if (const auto* s = node.as_string()) {
      auto it = enums_.find(s->get());
      if (it != enums_.end())
        spec.values = it->second;
      else
        fail(node.source(), "no enum named '" + s->get() + "' in [enums]");
    } else {
      fail(node.source(), "values must be a table { 0 = \"off\" } or the name of an [enums] table");
    }
  }

  detail::DiagnosticList problems_;
  std::map<std::string, std::vector<SpecValue>, std::less<>> enums_;
  Dialect dialect_ = Dialect::Gsl;
  bool dialect_known_ = false;
};

}  // namespace

RegisterMapResult load_register_map(std::string_view toml_text, std::string_view source_name) {
  toml::table root;
  try {
    root = toml::parse(toml_text, source_name);
  } catch (const toml::parse_error& e) {
    MapDiagnostic d{std::string(source_name), line_of(e.source()), column_of(e.source()),
                    std::string(e.description())};
    return RegisterMapResult::failure({std::move(d)});
  }
  return MapFileReader(source_name).read(root);
}

}  // namespace pvtap
