// What the specification allows a request to ask: the quantity ranges of the Modbus reads and
// writes.
#pragma once

#include <cstdint>
#include <optional>

#include "pvtap/codec/frame.h"

namespace pvtap {

// QuantityProblem: a request quantity outside the range its function allows.
struct QuantityProblem {
  unsigned found = 0;
  unsigned min = 1;
  unsigned max = 0;
  bool write_part = false;  // 0x17: the quantity written, not the one read
};

// The largest quantity a request of `function` may ask for (the read part of 0x17), or
// nullopt for a function without a quantity field; the smallest is always 1.
std::optional<unsigned> max_quantity(std::uint8_t function);

// WriteCountProblem: a write request whose byte count disagrees with the quantity it writes.
struct WriteCountProblem {
  unsigned byte_count = 0;  // as the request says
  unsigned quantity = 0;    // registers or coils written
  unsigned expected = 0;    // the byte count that quantity needs
};

// The byte count rule a GSL or plain Modbus write breaks, if any (section 6 of PROTOCOLS.md):
//   0x0F  n = ceil(quantity / 8)     0x10  n = 2 * quantity     0x17  n = 2 * write quantity
std::optional<WriteCountProblem> write_count_problem(const Frame& request);

// Whether a Modbus-family request of `function` may go to every station at address 0 (writes,
// and diagnostics' force listen only mode). No station answers a broadcast.
bool may_broadcast(std::uint8_t function);

// A request to address 0 that the specification does not allow to be broadcast (a read, say):
// no station answers it, so it is a finding, not a timeout. Its check must be good: a damaged
// request's address may be the damaged byte.
bool broadcast_not_allowed(const FrameHeader& request, bool check_ok);

// The quantity rule a GSL or plain Modbus request breaks, if any (section 6 of PROTOCOLS.md):
//   0x01 0x02  1-2000     0x03 0x04  1-125     0x0F  1-1968
//   0x10       1-123      0x17       read 1-125, write 1-121
std::optional<QuantityProblem> quantity_problem(const Frame& request);

}  // namespace pvtap
