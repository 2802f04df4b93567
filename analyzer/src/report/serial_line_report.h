// What a bus decoded from logic samples reports about its serial line: settings and errors.
#pragma once

#include <cstdint>
#include <string>

namespace pvtap::analyzer {

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
  std::string channel;    // the logic channel it was read from, as the recording names it
  std::uint64_t framing_errors = 0;
  std::uint64_t parity_errors = 0;
  std::uint64_t breaks = 0;
  // Bytes of RS485 drivers switching on or off, kept out of the frames and the noise.
  std::uint64_t driver_glitches = 0;
};

// The line in the text report (two lines) and in the summary's bus ("serial" and "line").
void append_serial_line_text(const SerialLineReport& line, std::string& o);
void append_serial_line_json(const SerialLineReport& line, std::string& o);

}  // namespace pvtap::analyzer
