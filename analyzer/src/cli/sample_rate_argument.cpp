// --samplerate: a number with an optional k, M or G.
#include "cli/sample_rate_argument.h"

#include <cstdio>
#include <exception>
#include <optional>

namespace pvtap::analyzer {
namespace {

// Samples per second; nullopt when `text` is no positive rate.
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

}  // namespace

bool read_sample_rate_option(const std::string& text, double& rate) {
  if (text.empty()) return true;
  const std::optional<double> given = sample_rate_from(text);
  if (!given) {
    std::fprintf(stderr, "pvtap: --samplerate %s: expected a rate such as 4000000, 4M or 500k\n",
                 text.c_str());
    return false;
  }
  rate = *given;
  return true;
}

}  // namespace pvtap::analyzer
