#include "lan/carrier_faults.h"

#include <algorithm>
#include <charconv>

namespace pvtap::sim {
namespace {

std::string kind_list(const std::vector<std::string>& kinds) {
  std::string out;
  for (const std::string& k : kinds) out += (out.empty() ? "" : " ") + k;
  return out;
}

}  // namespace

std::optional<CarrierFaults> parse_carrier_faults(std::string_view text,
                                                  const std::vector<std::string>& kinds,
                                                  std::string& error) {
  CarrierFaults faults;
  if (text == "none" || text.empty()) return faults;
  while (!text.empty()) {
    const auto comma = text.find(',');
    const std::string_view item = text.substr(0, comma);
    text = comma == std::string_view::npos ? std::string_view{} : text.substr(comma + 1);
    const auto eq = item.find('=');
    const std::string kind(item.substr(0, eq));
    const std::string_view number = eq == std::string_view::npos ? "" : item.substr(eq + 1);
    unsigned value = 0;
    const auto [end, ec] = std::from_chars(number.data(), number.data() + number.size(), value);
    const bool known = std::find(kinds.begin(), kinds.end(), kind) != kinds.end();
    if (!known || ec != std::errc{} || end != number.data() + number.size() || value > 100) {
      error = "bad carrier fault '" + std::string(item) +
              "' (expected kind=percent; kinds: " + kind_list(kinds) + ")";
      return std::nullopt;
    }
    faults.percent[kind] = value;
  }
  return faults;
}

}  // namespace pvtap::sim
