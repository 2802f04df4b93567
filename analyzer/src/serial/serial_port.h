// SerialPort: a serial device opened for listening only, in raw mode at the bus's settings.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include "report/live_report.h"
#include "serial/serial_line.h"

namespace pvtap::analyzer {

class SerialPort {
 public:
  SerialPort() = default;
  ~SerialPort();
  SerialPort(const SerialPort&) = delete;
  SerialPort& operator=(const SerialPort&) = delete;

  // Opens `path` read-only (a tap never drives the bus) and sets raw mode, the baud rate, the
  // parity and the stop bits, no flow control; false with error() when any step fails.
  // `mark_errors`: bytes with a framing or parity error come marked (PARMRK).
  bool open(const std::string& path, std::uint32_t baud, SerialLine line, bool mark_errors = false);
  // Sets another rate and format on the open port and drops what it read at the old ones.
  bool set_line(std::uint32_t baud, SerialLine line);
  void close();
  bool is_open() const { return fd_ >= 0; }
  int fd() const { return fd_; }

  // ReadResult: what one non-blocking read gave.
  enum class ReadResult { Data, Empty, Gone };
  // Reads what is waiting into `buffer`; `got` is the byte count for Data. Gone: the device
  // went away (unplugged adapter, closed pty) with error() saying how.
  ReadResult read(std::span<std::uint8_t> buffer, std::size_t& got);

  // The driver's line error counters (TIOCGICOUNT), or nullopt with error() saying why.
  std::optional<LineErrorCounts> line_errors();

  const std::string& error() const { return error_; }

 private:
  bool configure(std::uint32_t baud, SerialLine line);
  int fd_ = -1;
  bool mark_errors_ = false;
  std::string error_;
};

// The termios speeds a tap can be set to, as text for error messages ("2400, 4800, ...").
std::string supported_speeds_text();

}  // namespace pvtap::analyzer
