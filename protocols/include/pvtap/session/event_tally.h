// EventTally: the counts of one stream of session events, by one rule for what each event
// counts as (a damaged frame, an exception, a timeout). The session's report, a run's totals
// and the bus health MQTT publishes all count with it.
#pragma once

#include <cstdint>
#include <optional>

#include "pvtap/codec/function_codes.h"
#include "pvtap/session/bus_report.h"
#include "pvtap/session/bus_session.h"
#include "pvtap/statistics/distribution_summary.h"

namespace pvtap {

struct EventCounts {
  std::uint64_t frames = 0;          // every frame event, parsed or not
  std::uint64_t damaged_frames = 0;  // bad check
  // Exception and error replies whose check holds, but a gateway's 0x0B (gateway_timeouts).
  std::uint64_t exceptions = 0;
  std::uint64_t unsolicited = 0;
  std::uint64_t address_conflicts = 0;  // second replies with other contents (SessionFrame)
  // Good requests the device did not answer: no reply at all, or a gateway's 0x0B.
  std::uint64_t timeouts = 0;
  // Exceptions 0x0B: a gateway's timeout on the serial bus behind it (the request reached
  // the gateway, the device behind it did not answer): counted in timeouts, not exceptions.
  // A logger stick's code 05 in place of a reply says the same (TimeoutReason::CarrierNoReply).
  std::uint64_t gateway_timeouts = 0;
  std::uint64_t unanswered_damaged_requests = 0;
  std::uint64_t unanswered_at_end = 0;
  std::uint64_t unanswered_after_loss = 0;
  std::uint64_t noise_bytes = 0;
  GapTally gaps;
  LineErrorTally line_errors;

  EventCounts& operator+=(const EventCounts& o);
};

// TimedLatency: a reply's latency and when that reply ended.
struct TimedLatency {
  double latency = 0;
  double at = 0;
};

class EventTally {
 public:
  void add(const SessionFrame& f);
  void add(const SessionTimeout& t);
  void add(const SessionNoise& n) { counts_.noise_bytes += n.noise.bytes.size(); }
  void add(const SessionGap& g);
  void add(const SessionLineError& e);
  void add(const SessionDriverGlitch& g);
  // Adds the tally of another stream (the buses of a run).
  void merge(const EventTally& other);

  const EventCounts& counts() const { return counts_; }
  const DistributionAccumulator& latency() const { return latency_; }
  // The latest reply timed (by its end time over merged streams).
  std::optional<TimedLatency> last_latency() const { return last_latency_; }

 private:
  EventCounts counts_;
  DistributionAccumulator latency_;
  std::optional<TimedLatency> last_latency_;
};

// The code an exception reply carries (0xFF for a Hybrid error reply); nullopt for any other
// frame, and for a reply whose check fails, whose code cannot be trusted.
// Inline: every tally asks it of every frame.
inline std::optional<std::uint8_t> exception_code(const SessionFrame& f) {
  if (f.frame == nullptr || !f.check.ok || f.role != Role::Response) return std::nullopt;
  if (f.reply_kind == ReplyKind::GslException) return f.frame->exception_code;
  if (f.reply_kind == ReplyKind::HybridError) return fc::kHybridError;
  return std::nullopt;
}

// A gateway's 0x0B: the device behind it did not answer (a timeout, not the device's exception).
inline bool gateway_timeout(const SessionFrame& f) {
  const auto code = exception_code(f);
  return code && *code == fc::kGatewayTargetNoResponse && modbus_family(f.dialect);
}

}  // namespace pvtap
