#include "cli/station_map_argument.h"

#include <charconv>
#include <filesystem>

namespace pvtap::analyzer {
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
