// Driver turnaround from driver-enable (DE) channels: how long after a frame's last stop bit
// each talker releases its RS485 driver, per DE channel and station (--de NAME).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "pvtap/uart/uart_decoder.h"
#include "report/serial_line_report.h"

namespace pvtap::analyzer {

class TurnaroundWatch {
 public:
  // `drivers`: the DE channels' names; the bus's characters are `char_samples` long.
  TurnaroundWatch(std::vector<std::string> drivers, double sample_rate, double char_samples);

  // The next run of DE channel `driver` (high: the driver enabled).
  void driver_run(std::size_t driver, SampleRun run);
  // The bus's characters in order, without its glitches.
  void character(const UartCharacter& c);

  // Each DE channel's release after the frames whose end it follows, per station (the frame's
  // first byte).
  std::vector<DriverTurnaround> turnarounds() const;

 private:
  struct FrameEnd {
    std::uint8_t station = 0;
    std::uint64_t last_start = 0, last_end = 0;
  };
  void add_release(std::size_t driver, std::uint64_t fall,
                   std::vector<DriverTurnaround>& out) const;

  std::vector<std::string> drivers_;
  double sample_rate_, char_samples_;
  std::vector<std::uint64_t> position_;            // per DE channel: samples seen
  std::vector<std::vector<std::uint64_t>> falls_;  // per DE channel: where the driver let go
  std::vector<FrameEnd> frames_;  // stretches of characters between silences of 1.5
  std::uint8_t station_ = 0;
};

}  // namespace pvtap::analyzer
