#include "sources/live_loop.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "sources/stop_signal.h"
#include "sources/wall_clock.h"

namespace pvtap::analyzer {
namespace {

// The longest sleep when nothing is due: bytes and signals end it earlier; the bound only
// keeps a clock that jumps from holding the loop for long.
constexpr double kLongestSleep = 60.0;

}  // namespace

LiveLoop::LiveLoop(const LiveOptions& options, Pipeline& pipeline, RunOutput& output)
    : options_(options),
      pipeline_(pipeline),
      output_(output),
      status_(options.status_line),
      started_(wall_clock_seconds()) {}

bool LiveLoop::count_reached() const {
  return options_.count > 0 && pipeline_.buses().counts().frames >= options_.count;
}

bool LiveLoop::should_stop() const {
  if (stop_requested() || count_reached()) return true;
  return options_.duration > 0 && wall_clock_seconds() - started_ >= options_.duration;
}

double LiveLoop::wake_at(double now) const {
  double wake = now + kLongestSleep;
  // The core says when its buses can next decide something; the driver never re-derives it.
  for (const std::optional<double> due :
       {pipeline_.next_deadline(), status_.next_due(), output_.next_due()}) {
    if (due) wake = std::min(wake, *due);
  }
  if (options_.duration > 0) wake = std::min(wake, started_ + options_.duration);
  return wake;
}

void LiveLoop::after_wake(double now) {
  // Events go out as they happen, not when the buffer fills.
  if (output_.stdout_pending()) status_.clear();
  output_.flush();
  if (status_.due(now)) show_status(now);
  output_.tick(now);
}

void LiveLoop::show_status(double now) {
  const ReassemblerTotals sum = pipeline_.buses().totals();
  const EventTally tally = pipeline_.buses().tally();
  const std::optional<TimedLatency> last = tally.last_latency();
  char text[224];
  std::snprintf(text, sizeof text,
                "%s%s%llu bytes, %llu frames, %llu bad checks, %llu timeouts, last latency %s",
                status_note_.c_str(), status_note_.empty() ? "" : ", ",
                static_cast<unsigned long long>(sum.bytes_in),
                static_cast<unsigned long long>(sum.frames),
                static_cast<unsigned long long>(sum.bad_frames),
                static_cast<unsigned long long>(tally.counts().timeouts),
                last ? (std::to_string(std::lround(last->latency * 1e3)) + " ms").c_str() : "-");
  status_.show(now, text);
}

void LiveLoop::saw_time(double time) {
  last_time_ = std::max(last_time_, time);
}

void LiveLoop::end(double now, LiveSources& live) {
  status_.clear();
  live.seconds = now - started_;
  // --count is a stop the user asked for, not an interruption.
  live.stopped_by_signal = stop_requested() && !count_reached();
  if (!sample_clock_) saw_time(now);
}

}  // namespace pvtap::analyzer
