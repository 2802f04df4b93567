// `pvtap --version`: the program's version and what the build made of its Wireshark plugin.
#pragma once

#include <string>

namespace pvtap::analyzer {

// Where this build's plugin is and where it would be installed, as the build knows them;
// empty fields when Wireshark's development files were not found at configure time.
struct PluginBuild {
  std::string series;        // "4.0": a plugin loads only into this Wireshark series
  std::string build_path;    // the plugin in the build tree
  std::string install_path;  // where cmake --install and the package put it
};

// Names the plugin file that exists (installed, in the user's personal plugin folder, or in
// the build tree) rather than what the configuration could have built: a build of the
// program alone has no plugin, whatever Wireshark the machine has.
std::string version_text(const PluginBuild& plugin);

}  // namespace pvtap::analyzer
