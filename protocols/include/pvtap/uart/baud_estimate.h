// The bit rate of a line read from how long its pulses last.
#pragma once

#include <cstdint>
#include <optional>
#include <span>

#include "pvtap/uart/uart_decoder.h"

namespace pvtap {

// BaudEstimate: the measured rate, and the standard rate it is taken for.
struct BaudEstimate {
  double measured = 0;     // bits per second, from the pulses
  std::uint32_t baud = 0;  // the standard rate when within kSnapTolerance, else measured
  double deviation = 0;    // measured / nearest standard rate - 1
  bool snapped = false;    // baud is a standard rate
  static constexpr double kSnapTolerance = 0.02;
};

// The standard rates a measured one snaps to.
std::span<const std::uint32_t> standard_bauds();

// From the widths (in samples) of the pulses between edges: the shortest pulse that is common
// is one bit; whole multiples of it (up to a character's worth) refine it. nullopt when no
// width is common enough to be a bit.
std::optional<BaudEstimate> estimate_baud(std::span<const std::uint64_t> widths,
                                          double sample_rate);

// A measured rate taken for the nearest standard one when close enough.
BaudEstimate snap_baud(double measured);

}  // namespace pvtap
