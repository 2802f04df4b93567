#include "serial/device_tap.h"

#include <algorithm>
#include <utility>

namespace pvtap::analyzer {
namespace {

// Reopening after an unplug: first after 0.1 s, doubling to at most 2 s between attempts.
constexpr double kFirstRetry = 0.1;
constexpr double kLongestRetry = 2.0;

std::string line_text(std::uint32_t baud, SerialLine line) {
  return std::to_string(baud) + " 8" + line.parity + std::to_string(line.stop_bits);
}

LineErrorCounts operator-(const LineErrorCounts& a, const LineErrorCounts& b) {
  return {a.framing - b.framing, a.overrun - b.overrun, a.parity - b.parity, a.breaks - b.breaks,
          a.buffer_overrun - b.buffer_overrun};
}

LineErrorCounts operator+(const LineErrorCounts& a, const LineErrorCounts& b) {
  return {a.framing + b.framing, a.overrun + b.overrun, a.parity + b.parity, a.breaks + b.breaks,
          a.buffer_overrun + b.buffer_overrun};
}

}  // namespace

DeviceTap::DeviceTap(std::string path, std::uint32_t baud, SerialLine line)
    : path_(std::move(path)), baud_(baud), line_(line) {
  report_.path = path_;
  report_.line = line_text(baud, line);
}

bool DeviceTap::open() {
  if (!port_.open(path_, baud_, line_)) {
    report_.last_error = port_.error();
    return false;
  }
  latency_ = lower_latency_timer(path_);
  start_line_error_counts();
  return true;
}

void DeviceTap::count_read(std::size_t bytes) {
  ++report_.reads;
  report_.bytes += bytes;
}

void DeviceTap::went_away(double now) {
  report_.last_error = port_.error();
  close_line_error_counts();
  port_.close();
  ++report_.outages;
  gone_since_ = now;
  backoff_ = kFirstRetry;
  next_attempt_ = now + backoff_;
}

bool DeviceTap::try_reopen(double now) {
  if (open()) {
    report_.outage_seconds += now - *gone_since_;
    gone_since_.reset();
    return true;
  }
  backoff_ = std::min(backoff_ * 2, kLongestRetry);
  next_attempt_ = now + backoff_;
  return false;
}

void DeviceTap::start_line_error_counts() {
  line_errors_base_ = port_.line_errors();
  line_errors_last_ = line_errors_base_;
  if (line_errors_base_) {
    line_errors_supported_ = true;
  } else {
    report_.line_errors_note = port_.error();
  }
}

void DeviceTap::sample_line_errors() {
  if (!port_.is_open() || !line_errors_base_) return;
  if (auto now = port_.line_errors()) line_errors_last_ = now;
}

void DeviceTap::close_line_error_counts() {
  if (line_errors_base_ && line_errors_last_) {
    line_errors_before_ = line_errors_before_ + (*line_errors_last_ - *line_errors_base_);
  }
  line_errors_base_.reset();
  line_errors_last_.reset();
}

DeviceReport DeviceTap::report(double now) {
  DeviceReport r = report_;
  r.adapter = latency_.adapter;
  r.latency_timer_ms = latency_.ms;
  r.latency_note = latency_.note;
  sample_line_errors();
  if (line_errors_supported_) {
    LineErrorCounts total = line_errors_before_;
    if (line_errors_base_ && line_errors_last_) {
      total = total + (*line_errors_last_ - *line_errors_base_);
    }
    r.line_errors = total;
  }
  if (gone_since_) {
    r.lost_at_end = true;
    r.outage_seconds += now - *gone_since_;
  }
  return r;
}

}  // namespace pvtap::analyzer
