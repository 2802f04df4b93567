// When a frame was on the bus, and whether the capture's clock can tell.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "pvtap/codec/dialect.h"

namespace pvtap {

// FrameTiming: one frame's place in time, as the reassembler estimated it.
struct FrameTiming {
  std::uint64_t id = 0;
  Dialect dialect = kDefaultDialect;
  Role role = Role::Request;  // as corrected by the TransactionMatcher
  std::uint8_t station = 0;
  std::uint8_t function = 0;
  double start_time = 0;        // first byte began, seconds
  double end_time = 0;          // last byte ended, seconds
  double max_internal_gap = 0;  // largest silence between two bytes of the frame, seconds
  // The frame's start and count fields where it has them (a request's poll block), and
  // whether its check held.
  std::optional<std::uint16_t> start;
  std::optional<std::uint16_t> count;
  bool check_ok = true;
};

// TimestampQuality: whether timestamps resolve character times, and if not, why
// (e.g. "chunked timestamps from a USB adapter").
struct TimestampQuality {
  bool fine = true;
  std::string reason;
  std::string source;  // what stamped them, when known ("logic analyzer at 4 MS/s")
};

}  // namespace pvtap
