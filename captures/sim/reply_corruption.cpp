#include "reply_corruption.h"

namespace pvtap::sim {

void corrupt_one_byte(std::vector<std::uint8_t>& bytes, Dialect dialect, SimRandom& random) {
  if (dialect == Dialect::Ascii) {
    // A data hex digit becomes another hex digit: the frame still parses, its sum does not
    // match. Data starts after ACK, station (2), 'R', address (4); the sum and EOT end it.
    const auto last = static_cast<std::int64_t>(bytes.size()) - 6;
    const auto at = static_cast<std::size_t>(random.between(8, last));
    constexpr char kDigits[] = "0123456789abcdef";
    char next = kDigits[random.between(0, 15)];
    if (next == static_cast<char>(bytes[at])) next = next == '0' ? '1' : '0';
    bytes[at] = static_cast<std::uint8_t>(next);
    return;
  }
  // RTU: a data byte (after address, function, byte count; before the CRC) is flipped.
  const auto last = static_cast<std::int64_t>(bytes.size()) - 3;
  const auto at = static_cast<std::size_t>(random.between(3, last));
  bytes[at] = static_cast<std::uint8_t>(bytes[at] ^ random.between(1, 255));
}

}  // namespace pvtap::sim
