// The stations a row of the station map table names: "10" or "10, 11", each 1 to 247.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace pvtap::dissector {

// StationList: the stations in the order written, or why the text names none.
struct StationList {
  std::vector<std::uint8_t> stations;
  std::string problem;  // empty when the list is good

  bool ok() const { return problem.empty(); }
};

// Reads a comma-separated list of station addresses. Spaces around an address are allowed;
// an empty item, a station outside 1..247 (0 is the broadcast address) and a station named
// twice are problems.
StationList read_station_list(std::string_view text);

}  // namespace pvtap::dissector
