// The table "Station register maps" of invrtu's preferences: a register map file per station,
// as pvtap audit's --map STATION=FILE, so that a meter decodes with its own map on a bus of
// inverters that keep theirs.
#pragma once

#include <epan/prefs.h>

#include "pvtap/registers/register_decoder.h"

namespace pvtap::dissector {

// Registers the table (a Wireshark user access table) as a preference of `module`.
void register_station_map_table(module_t* module);

// Gives `decoder` the maps the table's rows give their stations, as the rows last applied
// left them; the register decoder is rebuilt with them whenever the table changes.
void use_station_maps(RegisterDecoder& decoder);

}  // namespace pvtap::dissector
