// Character times and the Modbus RTU silent intervals for a baud rate.
#pragma once

#include <cstdint>

namespace pvtap {

// BusTiming: t1 (one 10-bit character), t1.5 and t3.5 in seconds for a baud rate.
// Above 19200 baud the Modbus serial-line spec fixes t1.5 = 750 us and t3.5 = 1.75 ms.
struct BusTiming {
  explicit BusTiming(std::uint32_t baud_rate, unsigned bits_per_char = 10)
      : baud(baud_rate),
        char_time(static_cast<double>(bits_per_char) / static_cast<double>(baud_rate)),
        t15(baud_rate > 19200 ? 750e-6 : 1.5 * char_time),
        t35(baud_rate > 19200 ? 1.75e-3 : 3.5 * char_time) {}
  std::uint32_t baud;
  double char_time;
  double t15;
  double t35;
};

}  // namespace pvtap
