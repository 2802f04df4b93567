// SessionTimes: the times of one bus: the span of input seen, the half-duplex rule that no
// frame starts before the one before it ended, and the timing statistics of frames and
// replies.
#pragma once

#include <cstdint>
#include <limits>

#include "pvtap/codec/frame.h"
#include "pvtap/session/bus_session.h"
#include "pvtap/statistics/timing_statistics.h"

namespace pvtap::detail {

class SessionTimes {
 public:
  explicit SessionTimes(const BusSessionOptions& options);

  // Input arrived at `t` (nothing is kept for an input without timestamps). The span runs
  // from the first byte of a frame (add) or of input to the last input.
  void seen(double t);
  bool any() const { return any_; }
  double first() const { return first_; }
  double last() const { return last_; }

  // A frame's start is estimated back from its last byte at the configured baud rate; a pty
  // or a gateway that delivers faster would put a reply's start before its request's end.
  // The bus is half duplex: nothing starts before the frame before it ended.
  void settle_start(SessionFrame& out);
  // The frame's gaps and, for a reply, the latency of `station`, the request's.
  void add(const SessionFrame& out, const Frame& frame, std::optional<std::uint8_t> station,
           double max_inner_gap);
  TimingReport report(const TimestampQuality& quality) const { return timing_.report(quality); }
  std::uint64_t requests_while_reply_due() const { return timing_.requests_while_reply_due(); }

 private:
  bool has_timestamps_;
  bool untrusted_;  // timestamps declared too coarse for gaps
  TimingStatistics timing_;
  bool any_ = false;
  double first_ = 0;
  double last_ = 0;
  double bus_free_at_ = -std::numeric_limits<double>::infinity();  // end of the last frame
};

}  // namespace pvtap::detail
