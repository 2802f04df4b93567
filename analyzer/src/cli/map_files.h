// Register map files on the command line: one read for the core, the user's folder of maps,
// and a --map value that gives a map to stations (STATION[,STATION...]=FILE).
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "pvtap/registers/register_map.h"

namespace pvtap::analyzer {

// The map in the file at `path`, or why not: the core's diagnostics, or "cannot open the
// file" when it cannot be read. The file's text is handed to the core, which reads no files.
RegisterMapResult read_register_map_file(const std::string& path);

// $XDG_CONFIG_HOME/pvtap/maps, else $HOME/.config/pvtap/maps; empty when neither is set.
std::filesystem::path user_map_folder();

// The *.toml files of `folder`, sorted by name (the order the plugin reads its maps in);
// none when the folder does not exist.
std::vector<std::string> user_map_files(const std::filesystem::path& folder);

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
