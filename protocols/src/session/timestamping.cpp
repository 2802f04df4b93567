// apply_timestamping: which silences a carrier's timestamps can prove.
#include "pvtap/session/timestamping.h"

#include <charconv>
#include <string>
#include <utility>

#include "pvtap/statistics/bus_timing.h"

namespace pvtap {
namespace {

void declare_batched(BusSessionOptions& o, std::string note) {
  o.reassembler.timestamps = TimestampTrust::Untrusted;
  o.timestamp_note = std::move(note);
}

// A read returns what the adapter held back for up to its latency timer: longer than t1.5
// and the stamps cannot tell the bus's silences apart.
void apply_latency_timer(std::optional<int> ms, BusSessionOptions& o) {
  const BusTiming timing(o.reassembler.baud, o.reassembler.bits_per_char);
  if (!ms || *ms * 1e-3 <= timing.t15) return;
  declare_batched(o, "the adapter's USB latency timer is " + std::to_string(*ms) +
                         " ms: reads come in batches too coarse to judge t1.5/t3.5");
  // Bytes come late by at most the timer: a longer silence than that plus t3.5 was real.
  o.reassembler.boundary_gap = *ms * 1e-3 + timing.t35;
}

}  // namespace

void apply_timestamping(const TimestampFacts& c, BusSessionOptions& o) {
  switch (c.timestamping) {
    case Timestamping::SerialCharacters:
    case Timestamping::ExportedPdus:
      return;
    case Timestamping::SerialBatches:
      declare_batched(o,
                      "the capture's records are chunks read from a serial adapter: their "
                      "timestamps are batched (e.g. by a USB adapter's latency timer), not per "
                      "character");
      return;
    case Timestamping::GatewaySegments:
      declare_batched(
          o, "the timestamps are those of the gateway's TCP/UDP segments, not of bus characters");
      o.reassembler.boundary_gap = c.gateway_gap;
      o.reassembler.segment_ends_pin = true;
      return;
    case Timestamping::LoggerStickFrames:
      // Each frame is whole (the V5 frame pins its ends): nothing is left to prove by time.
      declare_batched(o,
                      "latency is measured at the LAN side: the timestamps are those of the "
                      "logger stick's Solarman V5 frames on TCP, not of bus characters");
      o.reassembler.boundary_gap = 0;
      return;
    case Timestamping::PlainDump:
      o.has_timestamps = false;
      o.reassembler.timestamps = TimestampTrust::Untrusted;
      return;
    case Timestamping::LiveSerial:
      apply_latency_timer(c.latency_timer_ms, o);
      return;
  }
}

// The sample clock vouches for every character's time, whatever the reassembler would guess
// from their pace.
void apply_sample_clock(double sample_rate, BusSessionOptions& o) {
  o.reassembler.timestamps = TimestampTrust::Trusted;
  char rate[32];
  const auto end = std::to_chars(rate, rate + sizeof rate, sample_rate / 1e6).ptr;
  o.timestamp_source = "logic analyzer at " + std::string(rate, end) + " MS/s";
}

}  // namespace pvtap
