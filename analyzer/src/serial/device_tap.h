// DeviceTap: one serial tap during a live capture: its port, its outages and reopening with
// backoff when the adapter goes away, and what the report says about it.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "report/live_report.h"
#include "serial/serial_line.h"
#include "serial/serial_port.h"
#include "serial/usb_latency_timer.h"

namespace pvtap::analyzer {

class DeviceTap {
 public:
  DeviceTap(std::string path, std::uint32_t baud, SerialLine line);

  // Opens the device (and lowers an FTDI latency timer); false with error() when it cannot.
  bool open();
  const std::string& error() const { return port_.error(); }
  const std::string& path() const { return path_; }
  const LatencyTimerState& latency_timer() const { return latency_; }

  // The descriptor to poll, -1 while the device is gone.
  int fd() const { return port_.fd(); }
  SerialPort& port() { return port_; }
  void count_read(std::size_t bytes);

  // The device went away at `now`: closes it and schedules the first reopening attempt.
  void went_away(double now);
  bool gone() const { return gone_since_.has_value(); }
  // When to try reopening next; only while gone().
  double next_attempt() const { return next_attempt_; }
  // Tries to reopen; true when the device is back (the outage is then over).
  bool try_reopen(double now);
  double outage_started() const { return gone_since_.value_or(0); }

  // Samples the line error counters now and then, so that an unplug loses little of them.
  void sample_line_errors();
  DeviceReport report(double now);

 private:
  void start_line_error_counts();
  void close_line_error_counts();

  std::string path_;
  std::uint32_t baud_;
  SerialLine line_;
  SerialPort port_;
  LatencyTimerState latency_;
  DeviceReport report_;
  std::optional<double> gone_since_;
  double next_attempt_ = 0;
  double backoff_ = 0;
  // Counters are cumulative per port in the driver: report what changed while pvtap listened.
  std::optional<LineErrorCounts> line_errors_base_;
  std::optional<LineErrorCounts> line_errors_last_;
  LineErrorCounts line_errors_before_;  // of earlier openings (before unplugs)
  bool line_errors_supported_ = false;
};

}  // namespace pvtap::analyzer
