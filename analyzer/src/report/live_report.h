// What a live capture reports about its sources: serial taps and a network interface.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "report/serial_line_report.h"

namespace pvtap::analyzer {

// LineErrorCounts: a serial driver's error counters (TIOCGICOUNT) since the port was opened.
struct LineErrorCounts {
  std::uint64_t framing = 0;
  std::uint64_t overrun = 0;  // the UART's receive register overrun
  std::uint64_t parity = 0;
  std::uint64_t breaks = 0;
  std::uint64_t buffer_overrun = 0;  // the driver's buffer was full
};

// Counter by counter: the errors between two readings, and two taps' (or openings') sum.
inline LineErrorCounts operator-(const LineErrorCounts& a, const LineErrorCounts& b) {
  return {a.framing - b.framing, a.overrun - b.overrun, a.parity - b.parity, a.breaks - b.breaks,
          a.buffer_overrun - b.buffer_overrun};
}
inline LineErrorCounts operator+(const LineErrorCounts& a, const LineErrorCounts& b) {
  return {a.framing + b.framing, a.overrun + b.overrun, a.parity + b.parity, a.breaks + b.breaks,
          a.buffer_overrun + b.buffer_overrun};
}

// DeviceReport: one serial tap over the whole capture.
struct DeviceReport {
  std::string path;     // as given
  std::string line;     // "9600 8N1"
  std::string adapter;  // the tty the path resolved to ("ttyUSB0"), when known
  // The USB latency timer in ms, when the adapter has one (FTDI); and what pvtap did to it.
  std::optional<int> latency_timer_ms;
  std::string latency_note;
  // Line error counters, or why the driver cannot give them.
  std::optional<LineErrorCounts> line_errors;
  std::string line_errors_note;
  std::uint64_t reads = 0;
  std::uint64_t bytes = 0;
  std::uint64_t outages = 0;  // times the device went away (unplugged) and came back or not
  double outage_seconds = 0;  // total time without the device
  bool lost_at_end = false;   // the device was gone when the capture stopped
  std::string last_error;     // the last open/read error, for the report
  // --baud auto: the line the search settled on last; nullopt when it never settled.
  std::optional<SerialLineReport> found_line;
};

// InterfaceReport: a live network capture (libpcap's counters at the end).
struct InterfaceReport {
  std::string name;
  std::string filter;  // the BPF filter applied, empty for none
  std::string link_type;
  std::uint64_t packets = 0;                       // handed to pvtap
  std::optional<std::uint64_t> dropped;            // by the kernel (buffer full)
  std::optional<std::uint64_t> interface_dropped;  // by the interface or driver
};

// LiveSources: every source of a live capture; empty for audits of files.
struct LiveSources {
  std::vector<DeviceReport> devices;
  std::optional<InterfaceReport> interface;
  bool stopped_by_signal = false;
  double seconds = 0;  // how long the capture ran
  bool active() const { return !devices.empty() || interface.has_value(); }
};

}  // namespace pvtap::analyzer
