// Register map files on the command line: reading, finding, and naming their stations.
#include "cli/map_files.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <utility>

namespace pvtap::analyzer {

RegisterMapResult read_register_map_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    // The system's reason (no such file, permission denied), not a word on the map.
    MapDiagnostic d{path, 0, 0, std::string("cannot open the file: ") + std::strerror(errno)};
    return RegisterMapResult::failure({std::move(d)});
  }
  std::ostringstream text;
  text << in.rdbuf();
  return load_register_map(text.str(), path);
}

namespace fs = std::filesystem;

fs::path user_map_folder() {
  // The XDG rule: an empty or relative XDG_CONFIG_HOME is ignored.
  const char* config = std::getenv("XDG_CONFIG_HOME");
  if (config != nullptr && fs::path(config).is_absolute()) return fs::path(config) / "pvtap/maps";
  const char* home = std::getenv("HOME");
  if (home != nullptr && *home != '\0') return fs::path(home) / ".config/pvtap/maps";
  return {};
}

std::vector<std::string> user_map_files(const fs::path& folder) {
  std::vector<std::string> files;
  std::error_code ec;
  if (folder.empty() || !fs::is_directory(folder, ec)) return files;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    if (it->path().extension() == ".toml" && it->is_regular_file(ec)) {
      files.push_back(it->path().string());
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

namespace {

bool is_plain_file(std::string_view value, std::size_t equals) {
  if (equals == std::string_view::npos) return true;
  if (value.substr(0, equals).find('/') != std::string_view::npos) return true;
  std::error_code ignored;
  return std::filesystem::is_regular_file(std::filesystem::path(value), ignored);
}

std::string station_range() {
  return std::to_string(kFirstStation) + " to " + std::to_string(kLastStation);
}

// One station of the list, or a problem that says what is wrong with it. (The texts are built
// by appending: GCC 12 misreads operator+ chains of strings as overlapping copies.)
std::optional<std::uint8_t> station_of(std::string_view text, std::string& problem) {
  unsigned number = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), number);
  if (text.empty() || error != std::errc{} || end != text.data() + text.size()) {
    problem.append("'").append(text).append("' is not a station address (");
    problem.append(station_range()).append(")");
    return std::nullopt;
  }
  if (number < kFirstStation || number > kLastStation) {
    problem.append("station ").append(text).append(" is outside ").append(station_range());
    if (number == 0) problem.append(" (0 is the broadcast address)");
    return std::nullopt;
  }
  return static_cast<std::uint8_t>(number);
}

}  // namespace

std::optional<StationMapArgument> read_station_map_argument(std::string_view value) {
  const std::size_t equals = value.find('=');
  if (is_plain_file(value, equals)) return std::nullopt;
  StationMapArgument out;
  out.path = std::string(value.substr(equals + 1));
  std::string_view list = value.substr(0, equals);
  while (out.problem.empty()) {
    const std::size_t comma = list.find(',');
    if (const auto station = station_of(list.substr(0, comma), out.problem)) {
      out.stations.push_back(*station);
    }
    if (comma == std::string_view::npos) break;
    list.remove_prefix(comma + 1);
  }
  if (out.problem.empty() && out.path.empty()) out.problem = "no map FILE after '='";
  return out;
}

}  // namespace pvtap::analyzer
