#include "session/session_times.h"

#include <algorithm>

namespace pvtap::detail {

SessionTimes::SessionTimes(const BusSessionOptions& options)
    : has_timestamps_(options.has_timestamps),
      untrusted_(options.reassembler.timestamps == TimestampTrust::Untrusted),
      timing_(BusTiming(options.reassembler.baud, options.reassembler.bits_per_char)) {}

void SessionTimes::seen(double t) {
  if (!has_timestamps_) return;
  if (!any_) {
    first_ = last_ = t;
    any_ = true;
  }
  first_ = std::min(first_, t);
  last_ = std::max(last_, t);
}

void SessionTimes::settle_start(SessionFrame& out) {
  if (!has_timestamps_ || out.end_time < bus_free_at_) return;
  if (out.start_time < bus_free_at_) out.start_time = bus_free_at_;
  bus_free_at_ = out.end_time;
}

void SessionTimes::add(const SessionFrame& out, const Frame& frame,
                       std::optional<std::uint8_t> station, double max_inner_gap) {
  if (!has_timestamps_) return;
  // A frame's first byte came before the chunk that ended it: the span begins there.
  first_ = std::min(first_, out.start_time);
  if (out.echo) {
    FrameTiming echo;
    echo.end_time = out.end_time;
    timing_.add_echo(echo);
    return;
  }
  // With timestamps declared too coarse the bus gaps are never judged (the report says why
  // instead): no frame feeds the gap statistics, but the requests' poll periods and their
  // order against replies (a frame's span is placed within a batch) are still kept.
  const FrameTiming timing{out.id,         frame.dialect,  out.role,     frame.station,
                           frame.function, out.start_time, out.end_time, max_inner_gap,
                           frame.start,    frame.count,    out.check.ok};
  if (untrusted_) {
    timing_.add_frame_without_gaps(timing);
  } else {
    timing_.add_frame(timing);
  }
  if (out.latency) timing_.add_latency(station, *out.latency);
}

}  // namespace pvtap::detail
