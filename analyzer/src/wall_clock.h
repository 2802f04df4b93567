// The capture clock of live sources: wall-clock time, as pcap timestamps are.
#pragma once

#include <ctime>

namespace pvtap::analyzer {

// Seconds since the Unix epoch, to the nanosecond the clock gives.
inline double wall_clock_seconds() {
  timespec t{};
  clock_gettime(CLOCK_REALTIME, &t);
  return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_nsec) * 1e-9;
}

}  // namespace pvtap::analyzer
