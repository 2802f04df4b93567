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
    if (!untrusted_) timing_.add_echo(echo);
    return;
  }
  // With timestamps declared too coarse the bus gaps are never judged (the report says why
  // instead): requests alone give the poll periods, and no frame feeds the gap statistics.
  if (untrusted_) {
    if (out.role == Role::Request) {
      timing_.add_frame_without_gaps(FrameTiming{
          out.id, frame.dialect, out.role, frame.station, frame.function, out.start_time,
          out.end_time, max_inner_gap, frame.start, frame.count, out.check.ok});
    }
  } else {
    timing_.add_frame(FrameTiming{out.id, frame.dialect, out.role, frame.station, frame.function,
                                  out.start_time, out.end_time, max_inner_gap, frame.start,
                                  frame.count, out.check.ok});
  }
  if (out.latency) timing_.add_latency(station, *out.latency);
}

}  // namespace pvtap::detail
