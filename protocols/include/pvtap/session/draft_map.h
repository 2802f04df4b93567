// A draft register map of one station, written from what the session inferred of the words no
// map names (StationSummary::inferred), in the TOML format load_register_map reads: one entry
// per inferred value, keyed by table and address ("reg_0x083c"), its evidence, range and hint
// as comments. Sans I/O: the caller writes the text where it wants.
#pragma once

#include <cstdint>
#include <string>

#include "pvtap/session/bus_report.h"

namespace pvtap {

// The draft map's text, or an empty string when the station has no inferred block. `source`
// names the capture in the heading comment.
std::string draft_register_map(const StationSummary& station, std::string_view source);

}  // namespace pvtap
