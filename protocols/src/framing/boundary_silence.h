// BoundarySilence: which silence proves a frame boundary, and whether timestamps can show it.
#pragma once

#include <optional>
#include <string_view>

#include "pvtap/framing/stream_reassembler.h"
#include "pvtap/statistics/bus_timing.h"

namespace pvtap::detail {

// t3.5 proves a boundary while the timestamps are trusted; once they turn out batched, only
// the boundary gap (the adapter's latency and more) does, and none when it is 0.
class BoundarySilence {
 public:
  // `boundary_gap`: see ReassemblerOptions (the gap already resolved).
  BoundarySilence(const BusTiming& timing, TimestampTrust trust, double boundary_gap);

  bool proves(double gap) const {
    if (trusted_) return gap + kGapToleranceChars * timing_.char_time >= timing_.t35;
    return boundary_gap_ > 0 && gap >= boundary_gap_;
  }
  // The shortest silence that proves a boundary, before rounding; nullopt when none can.
  std::optional<double> shortest() const;

  // Under TimestampTrust::Auto, stops trusting the timestamps for the reason given.
  void distrust(std::string_view why);
  bool trusted() const { return trusted_; }
  std::string_view reason() const { return reason_; }

 private:
  // A silence counts as t3.5 when it is within a tenth of a character of it.
  static constexpr double kGapToleranceChars = 0.1;

  BusTiming timing_;
  TimestampTrust mode_;
  double boundary_gap_;
  bool trusted_;
  std::string_view reason_;
};

}  // namespace pvtap::detail
