// DeviceTap: one serial tap during a live capture: its port, its outages and reopening with
// backoff when the adapter goes away, and what the report says about it.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "report/live_report.h"
#include "serial/auto_baud.h"
#include "serial/device_outage.h"
#include "serial/line_error_tally.h"
#include "serial/serial_line.h"
#include "serial/serial_port.h"
#include "serial/usb_latency_timer.h"

namespace pvtap::analyzer {

class DeviceTap {
 public:
  // `search`: the rate and format are searched (--baud auto); baud and line are not used.
  DeviceTap(std::string path, std::uint32_t baud, SerialLine line, bool search = false);

  // Opens the device (and lowers an FTDI latency timer); false with error() when it cannot.
  bool open();
  const std::string& error() const { return port_.error(); }
  const std::string& path() const { return path_; }
  const LatencyTimerState& latency_timer() const { return latency_; }

  // Its fd() is -1 while the device is gone.
  SerialPort& port() { return port_; }
  // The search of its rate and format; null when they were given.
  AutoBaud* search() { return search_.get(); }
  // Sets the port to the search's current setting; false with error() when the driver refuses.
  bool follow_search();
  void count_read(std::size_t bytes);

  // The device went away at `now`: closes it and schedules the first reopening attempt.
  void went_away(double now);
  const DeviceOutage& outage() const { return outage_; }
  // Tries to reopen; true when the device is back (the outage is then over).
  bool try_reopen(double now);

  // Samples the line error counters now and then, so that an unplug loses little of them.
  void sample_line_errors();
  DeviceReport report(double now);

 private:
  std::string path_;
  std::uint32_t baud_;
  SerialLine line_;
  SerialPort port_;
  LatencyTimerState latency_;
  DeviceReport report_;
  DeviceOutage outage_;
  LineErrorTally line_errors_;
  std::unique_ptr<AutoBaud> search_;
};

}  // namespace pvtap::analyzer
