// Reads one [[coil]] or [[discrete_input]] table of a map file as a spec (private to the core).
#pragma once

#include <toml++/toml.h>

#include "registers/map_node_reader.h"
#include "registers/register_map_builder.h"

namespace pvtap::detail {

// The table's name in map files: "coil" or "discrete_input".
std::string_view coil_table_name(CoilTable table);

// The entry's address, key and name; unknown fields and wrong types go to `nodes`.
CoilSpec read_coil_entry(MapNodeReader& nodes, const toml::table& table, CoilTable kind);

}  // namespace pvtap::detail
