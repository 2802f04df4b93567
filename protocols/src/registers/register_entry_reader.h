// The entries of a map file as specs: [[register]], [[coil]], [[discrete_input]] (private to the
// core).
#pragma once

#include <toml++/toml.h>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "registers/map_node_reader.h"
#include "registers/register_map_builder.h"

namespace pvtap::detail {

// EnumTables: the [enums] of a map file by name, for entries that name one as their values.
using EnumTables = std::map<std::string, std::vector<SpecValue>, std::less<>>;

// Reads the fields of an entry one by one and combines those that depend on each other
// (address and last, kind and values) once all are read; the builder checks the rest.
class RegisterEntryReader {
 public:
  RegisterEntryReader(MapNodeReader& nodes, Dialect dialect, const EnumTables& enums)
      : nodes_(nodes), dialect_(dialect), enums_(enums) {}

  RegisterSpec read(const toml::table& table);

 private:
  // Fields of the table still to be combined after all have been read.
  struct PendingFields {
    std::optional<std::int64_t> last;
    bool has_address = false;
    bool has_kind = false;
    bool has_words = false;
    std::uint32_t last_line = 0;
    std::uint32_t last_column = 0;
  };

  static RegisterKind inferred_kind(const RegisterSpec& spec);
  void apply_last(RegisterSpec& spec, const PendingFields& pending);
  void read_field(const toml::key& key, const toml::node& node, RegisterSpec& spec,
                  PendingFields& pending);
  void read_option_field(const toml::key& key, const toml::node& node, RegisterSpec& spec);
  void read_kind(const toml::node& node, RegisterSpec& spec);
  void read_scale(const toml::node& node, RegisterSpec& spec);
  void read_combine(const toml::node& node, RegisterSpec& spec);
  void read_word_order(const toml::node& node, RegisterSpec& spec);
  void read_values(const toml::node& node, RegisterSpec& spec);

  MapNodeReader& nodes_;
  Dialect dialect_;
  const EnumTables& enums_;
};

// A [[coil]] or [[discrete_input]] entry: address, key and name; unknown fields and wrong types
// go to `nodes`.
CoilSpec read_coil_entry(MapNodeReader& nodes, const toml::table& table, CoilTable kind);

}  // namespace pvtap::detail
