// The short names of character formats.
#include "pvtap/uart/uart_format.h"

namespace pvtap {

const char* parity_name(Parity parity) {
  switch (parity) {
    case Parity::Even:
      return "even";
    case Parity::Odd:
      return "odd";
    case Parity::None:
      break;
  }
  return "none";
}

std::string format_name(const UartFormat& format) {
  const char letter = format.parity == Parity::Even  ? 'E'
                      : format.parity == Parity::Odd ? 'O'
                                                     : 'N';
  return std::to_string(format.data_bits) + letter + std::to_string(format.stop_bits);
}

}  // namespace pvtap
