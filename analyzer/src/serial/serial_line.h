// SerialLine: the character format of a tapped RS485 line besides its baud rate (the tap
// must match the bus, or characters read as framing or parity errors).
#pragma once

#include <string_view>

namespace pvtap::analyzer {

struct SerialLine {
  char parity = 'N';  // 'N', 'E' or 'O'
  int stop_bits = 1;

  // Bits on the wire per character: start, 8 data, parity, stop.
  unsigned bits_per_char() const {
    return 9u + (parity == 'N' ? 0u : 1u) + static_cast<unsigned>(stop_bits);
  }

  // The letter for a parity as the command line and Wireshark's dialog name it: "none",
  // "even" or "odd".
  static char parity_letter(std::string_view name) {
    if (name == "even") return 'E';
    if (name == "odd") return 'O';
    return 'N';
  }
};

}  // namespace pvtap::analyzer
