// sample_rate_from: a number with an optional k, M or G.
#include "cli/sample_rate_argument.h"

#include <exception>

namespace pvtap::analyzer {

std::optional<double> sample_rate_from(const std::string& text) {
  std::size_t used = 0;
  double rate = 0;
  try {
    rate = std::stod(text, &used);
  } catch (const std::exception&) {
    return std::nullopt;
  }
  const std::string unit = text.substr(used);
  if (unit == "k" || unit == "K")
    rate *= 1e3;
  else if (unit == "M")
    rate *= 1e6;
  else if (unit == "G")
    rate *= 1e9;
  else if (!unit.empty())
    return std::nullopt;
  if (!(rate > 0)) return std::nullopt;
  return rate;
}

}  // namespace pvtap::analyzer
