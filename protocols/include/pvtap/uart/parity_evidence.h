// Which parity a line carries, told from the bytes a UART set to 8N1 read with framing errors.
#pragma once

#include <cstdint>
#include <optional>

#include "pvtap/uart/uart_format.h"

namespace pvtap {

// ParityEvidence: read at 8N1, an 8E1 or 8O1 line puts its parity bit where the stop bit is
// expected, so a byte fails exactly when its parity bit is 0. Under even parity that bit is
// 0 when the data bits hold an even count of ones; under odd parity, an odd count.
class ParityEvidence {
 public:
  // A byte read at 8N1; `error` is a framing (or parity) error the driver marked.
  void add(std::uint8_t value, bool error);
  void clear() { *this = ParityEvidence{}; }

  // Even or Odd when enough bytes failed and (nearly) every byte agrees with that parity;
  // nullopt when the errors follow no parity (or there are too few to tell).
  std::optional<Parity> verdict() const;
  std::uint64_t errors() const { return failed_[0] + failed_[1]; }
  std::uint64_t bytes() const { return errors() + passed_[0] + passed_[1]; }

  // Errors a verdict needs, and the share of bytes that may disagree (line noise).
  static constexpr std::uint64_t kMinErrors = 4;
  static constexpr std::uint64_t kDisagreeOneIn = 32;

 private:
  // Indexed by the data bits' count of ones modulo 2.
  std::uint64_t failed_[2] = {0, 0};
  std::uint64_t passed_[2] = {0, 0};
};

}  // namespace pvtap
