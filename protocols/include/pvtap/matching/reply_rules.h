// Which reply answers which request, and how long the reply should be.
#pragma once

#include <optional>

#include "pvtap/matching/frame_summary.h"
#include "pvtap/matching/match_events.h"

namespace pvtap {

// Classifies a reply as data, a Hybrid 0xFF error reply or a GSL exception.
ReplyKind reply_kind(const FrameSummary& reply);

// GSL and plain Modbus count as one dialect here: a station's label may be settled only
// after its first request.
bool same_dialect(Dialect a, Dialect b);

// Whether `reply` can answer `request`, ignoring stations (the caller picks the candidate by
// address): same dialect, and the same function, or the dialect's error form of it (Hybrid
// 0xFF answers any Hybrid request; GSL fc|0x80 answers fc). ASCII replies must also repeat
// the request's start address.
bool answers(const FrameSummary& request, const FrameSummary& reply);

// Whether the normal reply of a function repeats its request unchanged (Modbus family 0x05
// 0x06 0x08 0x15 0x16, PROTOCOLS.md sections 3 and 6): such an echo is the protocol's answer,
// nothing to note.
bool reply_is_echo(Dialect d, std::uint8_t function);

// Whether `frame`, reported as a request, is the echo of the pending `request` of a function
// whose reply repeats it (0x05 0x06 0x08 0x15 0x16): the same station, function and fields. A copy
// with a bad check is also taken as the echo, since a master repeating its write would send it with
// a good CRC.
bool echoes_write(const FrameSummary& request, const FrameSummary& frame, bool frame_check_ok);

// CountComparison: the length a reply should have had against the one it has.
struct CountComparison {
  unsigned expected = 0;
  unsigned found = 0;
  CountUnit unit = CountUnit::Bytes;
  bool matches() const { return expected == found; }
};

// The length rule for a reply to `request`, or nullopt when none applies (error replies,
// functions without a length field, missing fields):
//   Hybrid reads 0x11 0x12 0x16 0x17   n = 4 + 2*count
//   Hybrid 0x18 and 0x1F               n = 8 (device number + register/start + value/count)
//   GSL/Modbus 0x03 0x04 0x17          n = 2*count
//   Modbus 0x01 0x02                   n = ceil(count/8)
//   ASCII                              words in the reply = count of the request
std::optional<CountComparison> compare_reply_count(const FrameSummary& request,
                                                   const FrameSummary& reply);

}  // namespace pvtap
