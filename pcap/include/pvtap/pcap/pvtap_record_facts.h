// What pvtap's own exported-PDU records carry beyond their bytes (tags kTagPvtapRecord and
// kTagPvtapRun, exported_pdu_tags.h): the facts a later audit needs to give the same verdicts.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

#include "pvtap/codec/dialect.h"
#include "pvtap/framing/bus_chunk.h"

namespace pvtap {

// RecordKind: what the run that wrote a record decided its bytes are.
// End: the run ended; the record has no bytes, its time is the last its clock read. Loss:
// capture data was lost there (a gap); no bytes either.
enum class RecordKind : std::uint8_t { Frame = 1, Noise = 2, End = 3, Loss = 4 };

// RecordFacts: one record as its run decided and timed it.
struct RecordFacts {
  RecordKind kind = RecordKind::Frame;
  // The stream it was read from: Unknown for a tap, whose one stream holds both directions.
  Direction stream = Direction::Unknown;
  double start_time = 0.0;                  // the start of its first byte
  double end_time = 0.0;                    // the end of its last byte
  std::optional<std::uint64_t> lost_bytes;  // Loss: how many, when the run knew
};

// RunFacts: the settings of the run that wrote a record, and the bus it was on.
struct RunFacts {
  DialectSet dialects = DialectSet::all();
  std::uint32_t baud = 9600;
  double timeout = 1.0;  // seconds a request waited for its reply
  std::string_view bus;  // empty for the one bus of a serial input
};

// The dialects as the kTagPvtapRun byte holds them, and back.
std::uint8_t dialect_bits(DialectSet dialects);
DialectSet dialects_of_bits(std::uint8_t bits);

}  // namespace pvtap
