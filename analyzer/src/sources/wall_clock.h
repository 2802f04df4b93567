// The capture clock of live sources: wall-clock time, as pcap timestamps are.
#pragma once

#include <algorithm>
#include <cmath>
#include <ctime>

namespace pvtap::analyzer {

// Seconds since the Unix epoch, to the nanosecond the clock gives.
inline double wall_clock_seconds() {
  timespec t{};
  clock_gettime(CLOCK_REALTIME, &t);
  return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_nsec) * 1e-9;
}

// The time left until `wake_at` on the capture clock, as ppoll's timeout (zero when past).
inline timespec timeout_until(double wake_at) {
  const double seconds = std::max(wake_at - wall_clock_seconds(), 0.0);
  timespec t{};
  t.tv_sec = static_cast<time_t>(seconds);
  t.tv_nsec = static_cast<long>((seconds - std::floor(seconds)) * 1e9);
  return t;
}

}  // namespace pvtap::analyzer
