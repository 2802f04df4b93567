// What the two live sources of pvtap sniff (serial taps and a network interface) share:
// when to stop, the output as events happen, the status line, and the end of the capture.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "audit_bus.h"
#include "stop_signal.h"
#include "wall_clock.h"

namespace pvtap::analyzer {

bool AuditRun::count_reached() const {
  return options_.live.count > 0 && frames_seen_ >= options_.live.count;
}

bool AuditRun::live_should_stop(double started) const {
  if (stop_requested() || count_reached()) return true;
  const double duration = options_.live.duration;
  return duration > 0 && wall_clock_seconds() - started >= duration;
}

void AuditRun::flush_live_output(double now) {
  // Events go out as they happen, not when the buffer fills.
  if (!out_.buffer().empty()) {
    status_->clear();
    out_.flush();
  }
  if (status_->due(now)) show_status(now);
  if (mqtt_) mqtt_->tick(now);
}

void AuditRun::show_status(double now) {
  ReassemblerTotals sum;
  for (const auto& bus : buses_) {
    const ReassemblerTotals t = bus->session.totals();
    sum.bytes_in += t.bytes_in;
    sum.frames += t.frames;
    sum.bad_frames += t.bad_frames;
  }
  char text[160];
  std::snprintf(
      text, sizeof text, "%llu bytes, %llu frames, %llu bad checks, %llu timeouts, last latency %s",
      static_cast<unsigned long long>(sum.bytes_in), static_cast<unsigned long long>(sum.frames),
      static_cast<unsigned long long>(sum.bad_frames),
      static_cast<unsigned long long>(timeouts_seen_),
      last_latency_ ? (std::to_string(std::lround(*last_latency_ * 1e3)) + " ms").c_str() : "-");
  status_->show(now, text);
}

void AuditRun::end_live_capture(double started, double now) {
  status_->clear();
  live_.seconds = now - started;
  // --count is a stop the user asked for, not an interruption.
  live_.stopped_by_signal = stop_requested() && !count_reached();
  last_time_ = std::max(last_time_, now);
}

}  // namespace pvtap::analyzer
