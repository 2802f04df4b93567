// A sample rate as people write it on a command line: "4000000", "4M", "500k".
#pragma once

#include <optional>
#include <string>

namespace pvtap::analyzer {

// Samples per second; nullopt when `text` is no positive rate.
std::optional<double> sample_rate_from(const std::string& text);

}  // namespace pvtap::analyzer
