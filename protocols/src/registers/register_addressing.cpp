// Written register addresses versus wire addresses (only IDs read as hex differ: GSL's).
#include "pvtap/registers/register_decoder.h"

#include "dialects/dialect_module.h"

namespace pvtap {
namespace {

bool same_addresses(Dialect d, GslIdReading ids) {
  return !detail::dialect_module(d).decimal_register_ids || ids == GslIdReading::Decimal;
}

}  // namespace

std::optional<std::uint16_t> wire_address_of(Dialect d, std::uint16_t written, GslIdReading ids) {
  if (same_addresses(d, ids)) return written;
  if (written > 9999) return std::nullopt;
  // Each decimal digit of the written ID becomes one hex digit: 1050 -> 0x1050.
  unsigned wire = 0;
  for (unsigned scale = 1000; scale > 0; scale /= 10) wire = (wire << 4) | (written / scale % 10);
  return static_cast<std::uint16_t>(wire);
}

std::optional<std::uint16_t> written_address_of(Dialect d, std::uint16_t wire, GslIdReading ids) {
  if (same_addresses(d, ids)) return wire;
  unsigned written = 0;
  for (unsigned i = 0; i < 4; ++i) {
    const unsigned digit = (static_cast<unsigned>(wire) >> (12 - 4 * i)) & 0xFu;
    if (digit > 9) return std::nullopt;
    written = written * 10 + digit;
  }
  return static_cast<std::uint16_t>(written);
}

}  // namespace pvtap
