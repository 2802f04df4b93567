// Reads the TOML form of a register map into entry specs; the builder checks the rest.
#include <toml++/toml.h>

#include "pvtap/registers/register_map.h"
#include "pvtap/registers/sunspec.h"
#include "registers/map_node_reader.h"
#include "registers/register_entry_reader.h"
#include "registers/register_map_builder.h"

namespace pvtap {
namespace {

using detail::column_of;
using detail::line_of;

// MapFileReader: the settings and [enums] are read before any [[register]], wherever the file
// puts them: an entry's `last` depends on the dialect, and its `values` may name an enum.
class MapFileReader {
 public:
  explicit MapFileReader(std::string_view source) : nodes_(source) {}

  RegisterMapResult read(const toml::table& root) {
    detail::MapHeaderSpec header = read_header(root);
    if (!dialect_known_) return RegisterMapResult::failure(nodes_.take_problems());
    read_enums(root.get("enums"));
    RegisterMapBuilder builder(std::move(header));
    read_registers(root.get("register"), builder);
    read_coils(root.get("coil"), detail::CoilTable::Coils, builder);
    read_coils(root.get("discrete_input"), detail::CoilTable::DiscreteInputs, builder);
    const std::optional<SunSpecChain> chain = read_sunspec(root.get("sunspec"));
    if (chain) builder.defer_scale_factors();
    RegisterMapResult own = std::move(builder).build(nodes_.take_problems());
    if (!chain || !own) return own;
    // The file's own entries are laid over the chain's, so that a user can rename a point.
    RegisterMapResult of_chain = sunspec_register_map(*chain, nodes_.source());
    if (!of_chain) return of_chain;
    return merge_register_maps(of_chain.value(), own.value());
  }

 private:
  detail::MapHeaderSpec read_header(const toml::table& root) {
    detail::MapHeaderSpec header;
    header.source_name = nodes_.source();
    for (const auto& [key, node] : root) {
      const std::string_view name = key.str();
      if (name == "dialect") {
        read_dialect(node, header);
      } else if (name == "title") {
        if (const auto* s = nodes_.expect_string(node, "title")) header.title = s->get();
      } else if (name == "mode") {
        read_mode(node, header);
      } else if (!is_table_name(name)) {
        nodes_.fail(key.source(), "unknown setting '" + std::string(name) +
                                      "' (expected dialect, title, mode, [enums], [[register]], "
                                      "[[coil]] or [[discrete_input]])");
      }
    }
    if (!root.contains("dialect")) {
      nodes_.fail_at(
          1, 1,
          "the map must name its dialect: dialect = \"ascii\", \"hybrid\", \"gsl\" or \"modbus\"");
    }
    return header;
  }

  static bool is_table_name(std::string_view name) {
    return name == "enums" || name == "register" || name == "coil" || name == "discrete_input" ||
           name == "sunspec";
  }

  // [sunspec] base = 40000, models = [[1, 66], [103, 50]], ended = true: a SunSpec device's
  // chain as an earlier capture showed it, for a capture that starts after the master's scan.
  std::optional<SunSpecChain> read_sunspec(const toml::node* node) {
    if (node == nullptr) return std::nullopt;
    const auto* t = node->as_table();
    const toml::array* models = t != nullptr ? (*t)["models"].as_array() : nullptr;
    const std::optional<std::int64_t> base =
        t != nullptr ? (*t)["base"].value_exact<std::int64_t>() : std::nullopt;
    if (t == nullptr || models == nullptr || !base || *base < 0 || *base > 0xFFFD ||
        dialect_ != kSunSpecDialect) {
      nodes_.fail(node->source(),
                  "[sunspec] belongs to a modbus map and holds base = 40000 and models = [[id, "
                  "length], ...]");
      return std::nullopt;
    }
    SunSpecChain chain;
    chain.base = static_cast<std::uint16_t>(*base);
    chain.ended = (*t)["ended"].value_or(false);
    for (const toml::node& m : *models) {
      const toml::array* pair = m.as_array();
      const auto id =
          pair && pair->size() == 2 ? (*pair)[0].value_exact<std::int64_t>() : std::nullopt;
      const auto length =
          pair && pair->size() == 2 ? (*pair)[1].value_exact<std::int64_t>() : std::nullopt;
      if (!id || !length || *id < 0 || *id >= 0xFFFF || *length < 0 || *length > 0xFFFF ||
          !chain.append(static_cast<std::uint16_t>(*id), static_cast<std::uint16_t>(*length))) {
        nodes_.fail(m.source(),
                    "a [sunspec] model is [id, length] and the chain must end "
                    "before address 65535");
        return std::nullopt;
      }
    }
    return chain;
  }

  void read_coils(const toml::node* node, detail::CoilTable table, RegisterMapBuilder& builder) {
    if (node == nullptr) return;
    const std::string name(detail::coil_table_name(table));
    const auto* entries = node->as_array();
    if (entries == nullptr) {
      nodes_.fail(node->source(), name + " entries are written as [[" + name + "]]");
      return;
    }
    for (const toml::node& entry : *entries) {
      if (const auto* t = entry.as_table()) {
        builder.add(detail::read_coil_entry(nodes_, *t, table));
      } else {
        nodes_.fail(entry.source(), "each [[" + name + "]] entry must be a table");
      }
    }
  }

  void read_dialect(const toml::node& node, detail::MapHeaderSpec& header) {
    const auto* s = nodes_.expect_string(node, "dialect");
    if (s == nullptr) return;
    if (auto d = dialect_named(s->get())) {
      header.dialect = *d;
      dialect_ = *d;
      dialect_known_ = true;
    } else {
      nodes_.fail(node.source(),
                  "unknown dialect '" + s->get() + "' (expected ascii, hybrid, gsl or modbus)");
    }
  }

  void read_mode(const toml::node& node, detail::MapHeaderSpec& header) {
    const auto* s = nodes_.expect_string(node, "mode");
    if (s == nullptr) return;
    if (s->get() == "replace") {
      header.mode = MapMode::Replace;
    } else if (s->get() == "extend") {
      header.mode = MapMode::Extend;
    } else {
      nodes_.fail(node.source(), "unknown mode '" + s->get() + "' (expected replace or extend)");
    }
  }

  void read_enums(const toml::node* node) {
    if (node == nullptr) return;
    const auto* table = node->as_table();
    if (table == nullptr) {
      nodes_.fail(node->source(), "[enums] must be a table of value tables");
      return;
    }
    for (const auto& [key, entry] : *table) {
      if (const auto* values = entry.as_table()) {
        enums_[std::string(key.str())] = nodes_.read_number_table(*values, "value");
      } else {
        nodes_.fail(key.source(),
                    "enum '" + std::string(key.str()) + "' must be a table of values");
      }
    }
  }

  void read_registers(const toml::node* node, RegisterMapBuilder& builder) {
    if (node == nullptr) return;
    const auto* entries = node->as_array();
    if (entries == nullptr) {
      nodes_.fail(node->source(), "registers are written as [[register]] (an array of tables)");
      return;
    }
    detail::RegisterEntryReader entry_reader(nodes_, dialect_, enums_);
    for (const toml::node& entry : *entries) {
      const auto* table = entry.as_table();
      if (table == nullptr) {
        nodes_.fail(entry.source(), "each [[register]] entry must be a table");
        continue;
      }
      builder.add(entry_reader.read(*table));
    }
  }

  detail::MapNodeReader nodes_;
  detail::EnumTables enums_;
  Dialect dialect_ = kDefaultDialect;
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
