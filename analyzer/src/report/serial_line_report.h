// What a bus decoded from logic samples reports about its serial line: settings and errors.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "formatting/json_writer.h"

namespace pvtap::analyzer {

// DriverTurnaround: how long after a frame's last stop bit a driver-enable channel fell, over
// the frames of one station (their first byte); negative: before it ended (a truncated byte).
struct DriverTurnaround {
  std::string driver;  // the DE channel
  std::uint8_t station = 0;
  std::uint64_t frames = 0;
  std::uint64_t truncated = 0;  // frames whose last stop bit the driver cut short
  double min_us = 0, mean_us = 0, max_us = 0;
};

// SerialLineReport: the line's settings as found (or given) and the errors the UART saw.
struct SerialLineReport {
  std::uint32_t baud = 0;    // the standard rate, or the measured one rounded
  double measured_baud = 0;  // from the pulse widths
  double deviation = 0;      // measured / nearest standard rate - 1
  std::string parity;        // "none", "even", "odd"
  unsigned data_bits = 8;
  unsigned stop_bits = 1;
  bool inverted = false;  // the line idles low
  bool detected = true;   // found from the samples (not given)
  std::string how_found = "found from the samples";
  // A serial tap's search reads bytes, not pulses: no measured rate, and its line errors are
  // the driver's counters of the device's report.
  bool measured = true;
  bool has_line_errors = true;
  std::string channel;  // the logic channel it was read from, as the recording names it
  std::uint64_t framing_errors = 0;
  std::uint64_t parity_errors = 0;
  std::uint64_t breaks = 0;
  // Bytes of RS485 drivers switching on or off, kept out of the frames and the noise.
  std::uint64_t driver_glitches = 0;
  // A finding, once per bus: a channel's clock over 2 % off the nearest standard rate, which
  // a receiver at the standard rate may misread (a device's clock or setting to look at).
  std::uint64_t clock_deviations = 0;
  std::vector<DriverTurnaround> turnarounds;  // --de: per DE channel and station
};

// The line in the text report (two lines) and in the summary's bus ("serial" and "line").
void append_serial_line_text(const SerialLineReport& line, std::string& o);
void write_serial_line_json(JsonWriter& w, const SerialLineReport& line);

}  // namespace pvtap::analyzer
