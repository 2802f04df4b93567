#include "faults/fault_plan.h"

#include <algorithm>
#include <charconv>

namespace pvtap::sim {
namespace {

constexpr std::array<std::string_view, kFaultKinds> kNames{
    "corrupt",   "missing",         "slow",        "noise", "error_reply", "count_mismatch",
    "duplicate", "corrupt_request", "corrupt_data"};

std::optional<FaultKind> kind_named(std::string_view name) {
  for (unsigned i = 0; i < kFaultKinds; ++i)
    if (kNames[i] == name) return static_cast<FaultKind>(i);
  return std::nullopt;
}

}  // namespace

std::string_view to_string(FaultKind kind) {
  return kNames[static_cast<unsigned>(kind)];
}

std::optional<FaultPlan> parse_fault_plan(std::string_view text, std::string& error) {
  FaultPlan plan;
  if (text == "none" || text.empty()) return plan;
  if (text == "all") {
    // Opt-in kinds stay out, so that "all" keeps giving the bytes it always gave.
    std::fill_n(plan.percent.begin(), kFirstOptInKind, 4u);
    return plan;
  }
  while (!text.empty()) {
    const auto comma = text.find(',');
    const std::string_view item = text.substr(0, comma);
    text = comma == std::string_view::npos ? std::string_view{} : text.substr(comma + 1);
    const auto eq = item.find('=');
    const auto kind = kind_named(item.substr(0, eq));
    unsigned value = 0;
    const std::string_view number = eq == std::string_view::npos ? "" : item.substr(eq + 1);
    const auto [end, ec] = std::from_chars(number.data(), number.data() + number.size(), value);
    if (!kind || ec != std::errc{} || end != number.data() + number.size() || value > 100) {
      error = "bad fault '" + std::string(item) +
              "' (expected kind=percent; kinds: corrupt missing slow noise error_reply "
              "count_mismatch duplicate corrupt_request corrupt_data)";
      return std::nullopt;
    }
    plan[*kind] = value;
  }
  return plan;
}

}  // namespace pvtap::sim
