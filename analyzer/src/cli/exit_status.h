// The exit statuses of pvtap audit and pvtap sniff.
#pragma once

namespace pvtap::analyzer {

inline constexpr int kExitOk = 0;
inline constexpr int kExitFindings = 1;  // only with --fail-on errors
inline constexpr int kExitBadInput = 2;  // usage errors, unreadable input, unopenable sources

}  // namespace pvtap::analyzer
