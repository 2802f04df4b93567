// What the way bytes reach pvtap says about their timestamps, decided once for every program.
#pragma once

#include <cstdint>
#include <optional>

#include "pvtap/session/bus_session.h"

namespace pvtap {

// Timestamping: how the bytes of a bus were stamped with time on their way to pvtap (by the
// carrier that brought them: a serial tap, a gateway's segments, a dump without time, ...).
enum class Timestamping : std::uint8_t {
  SerialCharacters,   // serial records stamped as the characters arrived (a fine tap)
  SerialBatches,      // serial records that are chunks read from an adapter (batched stamps)
  GatewaySegments,    // a serial-to-TCP gateway's TCP/UDP segments
  PlainDump,          // a plain byte dump: no time at all
  LiveSerial,         // a live serial tap, read by pvtap itself
  ExportedPdus,       // exported-PDU records (pvtap audit --write), one frame each
  LoggerStickFrames,  // RTU frames a logger stick wrapped in Solarman V5 frames, one each
};

// TimestampFacts: the timestamping and what is known of its batching.
struct TimestampFacts {
  Timestamping timestamping = Timestamping::SerialCharacters;
  // GatewaySegments: the gateway's packing interval in seconds (pvtap's --gateway-gap).
  double gateway_gap = 0.0;
  // LiveSerial: the USB adapter's latency timer in ms, when the adapter has one.
  std::optional<int> latency_timer_ms;
};

// Sets what `options` trusts of the timestamps for `facts`: reassembler.timestamps,
// boundary_gap and segment_ends_pin, has_timestamps and timestamp_note. Reads the baud
// rate and bits per character already set in options.reassembler; leaves the rest alone.
void apply_timestamping(const TimestampFacts& facts, BusSessionOptions& options);

// Characters decoded from a logic analyzer's samples, each timed to a sample: t1.5 and t3.5 are
// judged on them (reassembler.timestamps = Trusted) and timestamp_source names the clock
// ("logic analyzer at 4 MS/s"). `sample_rate` in samples per second.
void apply_sample_clock(double sample_rate, BusSessionOptions& options);

}  // namespace pvtap
