// User register maps: the TOML files pvtap reads from the user's configuration folder.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace pvtap::analyzer {

// $XDG_CONFIG_HOME/pvtap/maps, else $HOME/.config/pvtap/maps; empty when neither is set.
std::filesystem::path user_map_folder();

// The *.toml files of `folder`, sorted by name (the order the plugin reads its maps in);
// none when the folder does not exist.
std::vector<std::string> user_map_files(const std::filesystem::path& folder);

}  // namespace pvtap::analyzer
