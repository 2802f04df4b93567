// AutoBaud: one serial tap whose rate and format are searched while it listens (pvtap sniff
// --baud auto): its reads go to the core's search until it settles, then to its bus.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "pvtap/uart/baud_search.h"
#include "report/serial_line_report.h"
#include "serial/marked_bytes.h"
#include "serial/serial_line.h"

namespace pvtap::analyzer {

class AutoBaud {
 public:
  // What a read or the passing of time did to the search.
  struct Outcome {
    bool change = false;   // the port must be set to baud() and line()
    bool settled = false;  // it settled just now
    bool lost = false;     // it had settled, and the line stopped making sense
  };

  std::uint32_t baud() const { return search_.setting().baud; }
  SerialLine line() const;
  bool settled() const { return search_.settled(); }
  // "19200 8E1".
  std::string setting_text() const;
  // For the status line: "searching: 4800 8N1" or "19200 8E1 found".
  std::string status_text() const;

  // BusBytes: what the bus is to read, each read with its own time.
  struct BusBytes {
    std::vector<std::uint8_t> bytes;
    std::vector<std::pair<std::size_t, double>> reads;  // (end in bytes, time) of each read
    void clear() {
      bytes.clear();
      reads.clear();
    }
  };

  // A read (PARMRK-marked) at `time`. `for_bus` gets what the bus is to read: nothing while
  // searching; on settling, the reads of the stretch that settled it.
  Outcome take(std::span<const std::uint8_t> read, double time, BusBytes& for_bus);
  Outcome tick(double time);

  // The line as found, for the summary; nullopt when it never settled.
  std::optional<SerialLineReport> report(const std::string& path) const;

 private:
  Outcome judge(bool was_settled, bool changed);

  BaudSearch search_;
  MarkedBytes marks_;
  std::vector<LineByte> bytes_;  // of the last read
  BusBytes held_;                // read at the current setting while searching
  bool ever_settled_ = false;
  LineSetting found_;  // the last setting it settled on
};

}  // namespace pvtap::analyzer
