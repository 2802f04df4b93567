#include "cli/version_text.h"

#include <cstdlib>
#include <filesystem>
#include <system_error>

namespace pvtap::analyzer {
namespace {

bool is_file(const std::string& path) {
  std::error_code error;
  return !path.empty() && std::filesystem::is_regular_file(path, error);
}

// Wireshark's personal plugin folder for a series (~/.local/lib/wireshark/plugins/4.0/epan).
std::string personal_plugin_path(const std::string& series) {
  const char* home = std::getenv("HOME");
  if (home == nullptr || *home == '\0') return {};
  return std::string(home) + "/.local/lib/wireshark/plugins/" + series + "/epan/pvtap.so";
}

std::string plugin_line(const PluginBuild& plugin) {
  if (plugin.series.empty())
    return "Wireshark plugin: not built (Wireshark's development files were not found when "
           "pvtap was configured; Debian: wireshark-dev)";
  const std::string head = "Wireshark plugin for Wireshark " + plugin.series + ": ";
  if (is_file(plugin.install_path)) return head + "installed, " + plugin.install_path;
  const std::string personal = personal_plugin_path(plugin.series);
  if (is_file(personal)) return head + "installed for this user, " + personal;
  if (is_file(plugin.build_path)) return head + "built, not installed, " + plugin.build_path;
  return head + "not built (cmake --build build --target pvtap_dissector)";
}

}  // namespace

std::string version_text(const PluginBuild& plugin) {
  return "pvtap " PVTAP_VERSION "\n" + plugin_line(plugin);
}

}  // namespace pvtap::analyzer
