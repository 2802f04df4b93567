#include "registers/coil_entry_reader.h"

#include <string>

namespace pvtap::detail {

std::string_view coil_table_name(CoilTable table) {
  return table == CoilTable::Coils ? "coil" : "discrete_input";
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
