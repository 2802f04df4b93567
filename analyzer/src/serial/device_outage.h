// DeviceOutage: a serial device gone since when, and when to try reopening it.
#pragma once

#include <optional>

namespace pvtap::analyzer {

// Attempts start soon (0.1 s, so that a replugged adapter is back quickly) and back off,
// doubling to at most 2 s, so that an absent one costs little.
class DeviceOutage {
 public:
  void begin(double now);
  // A reopening failed at `now`.
  void retry_later(double now);
  // The device is back at `now`: the outage's length.
  double end(double now);

  bool ongoing() const { return since_.has_value(); }
  double since() const { return since_.value_or(0); }
  // Only while ongoing().
  double next_attempt() const { return next_attempt_; }

 private:
  std::optional<double> since_;
  double next_attempt_ = 0;
  double backoff_ = 0;
};

}  // namespace pvtap::analyzer
