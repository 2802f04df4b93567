#include "pvtap/session/event_tally.h"

#include "pvtap/codec/function_codes.h"

namespace pvtap {

EventCounts& EventCounts::operator+=(const EventCounts& o) {
  frames += o.frames;
  damaged_frames += o.damaged_frames;
  exceptions += o.exceptions;
  unsolicited += o.unsolicited;
  address_conflicts += o.address_conflicts;
  timeouts += o.timeouts;
  gateway_timeouts += o.gateway_timeouts;
  unanswered_damaged_requests += o.unanswered_damaged_requests;
  unanswered_at_end += o.unanswered_at_end;
  unanswered_after_loss += o.unanswered_after_loss;
  noise_bytes += o.noise_bytes;
  gaps.gaps += o.gaps.gaps;
  gaps.lost_bytes += o.gaps.lost_bytes;
  gaps.gaps_of_unknown_size += o.gaps.gaps_of_unknown_size;
  line_errors += o.line_errors;
  return *this;
}

void EventTally::add(const SessionFrame& f) {
  ++counts_.frames;
  if (!f.check.ok) ++counts_.damaged_frames;
  if (gateway_timeout(f)) {
    ++counts_.timeouts;
    ++counts_.gateway_timeouts;
  } else if (exception_code(f)) {
    ++counts_.exceptions;
  }
  if (f.unsolicited) ++counts_.unsolicited;
  if (f.address_conflict) ++counts_.address_conflicts;
  if (f.latency) {
    latency_.add(*f.latency);
    last_latency_ = TimedLatency{*f.latency, f.end_time};
  }
}

void EventTally::add(const SessionTimeout& t) {
  switch (t.kind) {
    case UnansweredKind::Timeout:
      ++counts_.timeouts;
      // A logger stick's code 05, as a gateway's 0x0B: no reply on the bus behind it.
      if (t.timeout.reason == TimeoutReason::CarrierNoReply) ++counts_.gateway_timeouts;
      break;
    case UnansweredKind::DamagedRequest:
      ++counts_.unanswered_damaged_requests;
      break;
    case UnansweredKind::InputEnded:
      ++counts_.unanswered_at_end;
      break;
    case UnansweredKind::AfterLoss:
      ++counts_.unanswered_after_loss;
      break;
  }
}

void EventTally::add(const SessionGap& g) {
  ++counts_.gaps.gaps;
  if (g.lost_bytes) {
    counts_.gaps.lost_bytes += *g.lost_bytes;
  } else {
    ++counts_.gaps.gaps_of_unknown_size;
  }
}

// As a receiver counts them: a character with both errors counts under each.
void EventTally::add(const SessionLineError& e) {
  LineErrorTally& t = counts_.line_errors;
  t.framing_errors += e.kind == LineErrorKind::Framing || e.kind == LineErrorKind::FramingAndParity;
  t.parity_errors += e.kind == LineErrorKind::Parity || e.kind == LineErrorKind::FramingAndParity;
  t.breaks += e.kind == LineErrorKind::Break ? 1 : 0;
}

// A glitch's byte was read with its errors too, before it was known to be a glitch.
void EventTally::add(const SessionDriverGlitch& g) {
  LineErrorTally& t = counts_.line_errors;
  ++t.driver_glitches;
  t.framing_errors += g.framing_error ? 1 : 0;
  t.parity_errors += g.parity_error ? 1 : 0;
}

void EventTally::merge(const EventTally& other) {
  counts_ += other.counts_;
  latency_.merge(other.latency_);
  if (other.last_latency_ && (!last_latency_ || other.last_latency_->at >= last_latency_->at)) {
    last_latency_ = other.last_latency_;
  }
}

}  // namespace pvtap
