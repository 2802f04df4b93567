// What a UART set one way reads from a line driven another way: the bytes drawn as samples at
// the line's rate and format, read back by the core's decoder at the receiver's.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "pvtap/uart/baud_search.h"
#include "pvtap/uart/uart_decoder.h"
#include "uart_runs.h"

namespace pvtap::test {

// 16 samples per bit at 115200, and a whole number of them per bit at every standard rate.
inline constexpr double kLineSampleRate = 1843200;

// The characters a receiver set to `reader` reads from `bytes` sent back to back as `line`,
// the line idle before them and long enough after them for the receiver to finish.
inline std::vector<UartCharacter> received(std::span<const std::uint8_t> bytes,
                                           const LineSetting& line, const LineSetting& reader) {
  UartRuns runs(kLineSampleRate / line.baud, line.format);
  runs.idle(2 * line.format.bits_per_char()).bytes(bytes);
  // Two of the receiver's characters of idle line: whatever it was reading ends.
  const double reader_bits = 2.0 * reader.format.bits_per_char() * line.baud / reader.baud;
  runs.idle(reader_bits + 2 * line.format.bits_per_char());
  return decode_runs(UartLine{kLineSampleRate, static_cast<double>(reader.baud), reader.format},
                     runs.runs());
}

// The same as a tty hands them to a reader: a value and whether the driver marked it.
inline std::vector<LineByte> line_bytes(const std::vector<UartCharacter>& chars) {
  std::vector<LineByte> out;
  for (const UartCharacter& c : chars) {
    out.push_back(LineByte{static_cast<std::uint8_t>(c.value), c.framing_error || c.parity_error,
                           c.is_break});
  }
  return out;
}

}  // namespace pvtap::test
