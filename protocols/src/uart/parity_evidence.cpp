// ParityEvidence: framing errors against the parity of the data bits.
#include "pvtap/uart/parity_evidence.h"

#include <bit>

namespace pvtap {

void ParityEvidence::add(std::uint8_t value, bool error) {
  const unsigned odd = static_cast<unsigned>(std::popcount(value)) % 2;
  (error ? failed_ : passed_)[odd] += 1;
}

std::optional<Parity> ParityEvidence::verdict() const {
  if (errors() < kMinErrors) return std::nullopt;
  // Even parity: failures have an even count of ones, and bytes that read cleanly an odd one.
  const std::uint64_t against_even = failed_[1] + passed_[0];
  const std::uint64_t against_odd = failed_[0] + passed_[1];
  const std::uint64_t allowed = bytes() / kDisagreeOneIn;
  if (against_even <= allowed && against_even < against_odd) return Parity::Even;
  if (against_odd <= allowed && against_odd < against_even) return Parity::Odd;
  return std::nullopt;
}

}  // namespace pvtap
