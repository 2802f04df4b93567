// A --map value that gives a map to stations: STATION[,STATION...]=FILE.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace pvtap::analyzer {

// StationMapArgument: the stations a map file is for, or why the value names none.
struct StationMapArgument {
  std::vector<std::uint8_t> stations;
  std::string path;
  std::string problem;  // empty when the stations are good
};

// Station addresses a map can be given to: 0 is the broadcast address, 248..255 are reserved.
inline constexpr unsigned kFirstStation = 1;
inline constexpr unsigned kLastStation = 247;

// The stations and file of "10,11=meter.toml"; nullopt for a plain map FILE: a value without
// '=', one whose part before the first '=' holds a '/', or one that names an existing file.
std::optional<StationMapArgument> read_station_map_argument(std::string_view value);

}  // namespace pvtap::analyzer
