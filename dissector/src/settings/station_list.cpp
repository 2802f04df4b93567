#include "settings/station_list.h"

#include <algorithm>

namespace pvtap::dissector {
namespace {

constexpr unsigned kLastStation = 247;

std::string_view trimmed(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

// The station an item names, or 0 for none (0 itself is the broadcast address, never a
// station of its own).
unsigned station_of(std::string_view item) {
  if (item.empty() || item.size() > 3) return 0;
  unsigned value = 0;
  for (char c : item) {
    if (c < '0' || c > '9') return 0;
    value = value * 10 + static_cast<unsigned>(c - '0');
  }
  return value <= kLastStation ? value : 0;
}

std::string quoted(std::string_view s) {
  std::string out(1, '\'');
  out.append(s);
  out += '\'';
  return out;
}

}  // namespace

StationList read_station_list(std::string_view text) {
  StationList out;
  if (trimmed(text).empty()) {
    out.problem = "no station given: write one like 10, or several like 10,11";
    return out;
  }
  std::string_view rest = text;
  for (;;) {
    const std::size_t comma = rest.find(',');
    const std::string_view item = trimmed(rest.substr(0, comma));
    const unsigned station = station_of(item);
    if (station == 0) {
      out.problem = (item.empty() ? std::string("an empty item") : quoted(item)) +
                    " is not a station: stations are 1 to 247 (0 is the broadcast address)";
      return out;
    }
    const auto s = static_cast<std::uint8_t>(station);
    if (std::find(out.stations.begin(), out.stations.end(), s) != out.stations.end()) {
      out.problem = "station " + std::to_string(station) + " is named twice";
      return out;
    }
    out.stations.push_back(s);
    if (comma == std::string_view::npos) break;
    rest.remove_prefix(comma + 1);
  }
  return out;
}

}  // namespace pvtap::dissector
