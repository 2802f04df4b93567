// How characters are framed on an asynchronous serial line, and the line's rate.
#pragma once

#include <cstdint>
#include <string>

namespace pvtap {

enum class Parity : std::uint8_t { None, Even, Odd };

// UartFormat: the character frame (start bit, data bits LSB first, parity, stop bits).
struct UartFormat {
  unsigned data_bits = 8;
  Parity parity = Parity::None;
  unsigned stop_bits = 1;
  // The line idles low (an RS232-side probe, or swapped RS485 wires): space is high.
  bool inverted = false;

  // Bits from the start bit to the last stop bit.
  unsigned bits_per_char() const {
    return 1 + data_bits + (parity == Parity::None ? 0 : 1) + stop_bits;
  }
};

// UartLine: what a decoder needs to read a channel's samples.
struct UartLine {
  double sample_rate = 0;  // samples per second
  double baud = 9600;      // bits per second (a measured rate need not be a standard one)
  UartFormat format;

  double samples_per_bit() const { return sample_rate / baud; }
};

// "8N1", "8E1", "8O2": the usual short name of a format.
std::string format_name(const UartFormat& format);
const char* parity_name(Parity parity);  // "none", "even", "odd"

}  // namespace pvtap
