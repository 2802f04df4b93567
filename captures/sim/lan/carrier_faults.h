// CarrierFaults: how often each fault of a LAN carrier happens, parsed from "kind=percent,...".
#pragma once

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace pvtap::sim {

struct CarrierFaults {
  std::map<std::string, unsigned, std::less<>> percent;  // kinds not named: 0
  unsigned operator[](std::string_view kind) const {
    const auto it = percent.find(kind);
    return it == percent.end() ? 0 : it->second;
  }
};

// "none" or "quirk=20,drop=2"; nullopt with `error` set when a kind is not one of `kinds` or
// a number is not 0-100.
std::optional<CarrierFaults> parse_carrier_faults(std::string_view text,
                                                  const std::vector<std::string>& kinds,
                                                  std::string& error);

}  // namespace pvtap::sim
