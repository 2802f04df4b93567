// A sample rate as people write it on a command line: "4000000", "4M", "500k".
#pragma once

#include <string>

namespace pvtap::analyzer {

// --samplerate as given: `rate` from `text` (left as it is when `text` is empty); false, with
// the reason on stderr, when `text` is no rate.
bool read_sample_rate_option(const std::string& text, double& rate);

}  // namespace pvtap::analyzer
