#include "pvtap/matching/transaction_matcher.h"

#include <algorithm>
#include <cmath>

#include "dialects/dialect_module.h"
#include "pvtap/codec/function_codes.h"
#include "pvtap/matching/reply_rules.h"
#include "pvtap/matching/request_rules.h"

namespace pvtap {
namespace {

bool is_broadcast_request(const FrameSummary& f) {
  return detail::answered_broadcast(f.dialect, f.station);
}

// A Modbus request to address 0 goes to every station and is never answered: a write, or,
// with a good check, a request that may not be broadcast (a finding of the session's). A
// damaged read to address 0 is a request whose address may be the damaged byte.
bool is_unanswered_broadcast(const FrameSummary& f, bool check_ok) {
  if (!modbus_family(f.dialect) || f.station != fc::kModbusBroadcast) return false;
  return may_broadcast(f.function) || broadcast_not_allowed(f, check_ok);
}

// A good reply whose length is what the request asked for (or whose function has no such
// rule). Where two masters poll one station, a reply of the wrong length answers the other's
// request: two such replies are not two devices.
bool fits(const FrameSummary& request, const ObservedFrame& reply) {
  if (!reply.check_ok) return false;
  const auto counts = compare_reply_count(request, reply.frame);
  return !counts || counts->matches();
}

}  // namespace

TransactionMatcher::TransactionMatcher(MatcherConfig config) : config_(config) {}

FrameMatch TransactionMatcher::on_frame(const ObservedFrame& in) {
  timeouts_.clear();
  if (in.answers_pending && in.frame.role == Role::Response) keep_waiting_for(in);
  move_time_to(in.start_time);
  FrameMatch out;
  out.role = in.frame.role;
  if (is_echo(in)) {
    take_echo(in, out);
    return out;
  }
  if (out.role == Role::Request && !in.role_known) {
    const Slot& own = slots_[in.frame.station];
    if (own.state == SlotState::Pending && echoes_write(own.request.frame, in.frame, in.check_ok)) {
      out.role_correction = RoleCorrection{in.id, own.request.id, Role::Request, Role::Response};
      out.role = Role::Response;
    }
  }
  if (out.role == Role::Request) {
    on_request(in);
  } else {
    on_reply(in, out);
  }
  last_request_ = LastRequest{out.role == Role::Request && in.check_ok && in.content != 0, in.id,
                              in.frame.station, in.content, in.end_time};
  // The bus is busy until the frame's last byte; later timeouts are judged from there.
  now_ = std::max(now_, in.end_time);
  out.timeouts = timeouts_.view();
  return out;
}

bool TransactionMatcher::is_echo(const ObservedFrame& in) const {
  const LastRequest& last = last_request_;
  if (!config_.echo_within || !last.open || in.frame.role != Role::Request || !in.check_ok ||
      in.content != last.content || in.frame.station != last.station) {
    return false;
  }
  const double within = reply_is_echo(in.frame.dialect, in.frame.function)
                            ? config_.echoing_reply_within
                            : *config_.echo_within;
  return in.start_time - last.end_time <= within;
}

// The request's wait starts again at the echo's end; one echo per request.
void TransactionMatcher::take_echo(const ObservedFrame& in, FrameMatch& out) {
  out.echo = EchoedRequest{in.id, last_request_.id};
  last_request_.open = false;
  const bool broadcast = is_broadcast_request(in.frame);
  Slot& slot = slots_[broadcast ? RequestSlots::kBroadcast : in.frame.station];
  if (slot.state == SlotState::Pending && slot.request.id == out.echo->request_id) {
    slot.request.end_time = in.end_time;
    slot.request.deadline = in.end_time + config_.timeout;
  }
  now_ = std::max(now_, in.end_time);
  out.timeouts = timeouts_.view();
}

std::span<const Timeout> TransactionMatcher::advance(double now) {
  timeouts_.clear();
  move_time_to(now);
  return timeouts_.view();
}

// A deadline only moves later: next_deadline_ stays a lower bound.
void TransactionMatcher::keep_waiting_for(const ObservedFrame& reply) {
  Slot& own = slots_[reply.frame.station];
  if (own.state != SlotState::Pending) return;
  own.request.deadline = std::max(own.request.deadline, reply.start_time);
}

void TransactionMatcher::move_time_to(double now) {
  now_ = std::max(now_, now);
  if (now_ > next_deadline_) expire_overdue();
}

std::optional<double> TransactionMatcher::next_deadline() const {
  if (!std::isfinite(next_deadline_)) return std::nullopt;
  // A request times out once time has passed its deadline, not at it.
  return std::nextafter(next_deadline_, std::numeric_limits<double>::infinity());
}

std::span<const Timeout> TransactionMatcher::carrier_no_reply(std::uint8_t station, double now,
                                                              std::uint8_t code) {
  timeouts_.clear();
  Slot& slot = slots_[station];
  if (slot.state != SlotState::Pending) return timeouts_.view();
  give_up(slot, TimeoutReason::CarrierNoReply, std::max(0.0, now - slot.request.end_time),
          std::nullopt, code);
  next_deadline_ = slots_.earliest_deadline();
  return timeouts_.view();
}

std::span<const Timeout> TransactionMatcher::finish() {
  timeouts_.clear();
  for (Slot* slot : slots_.pending_by_deadline(false, now_)) {
    give_up(*slot, TimeoutReason::CaptureEnded, std::max(0.0, now_ - slot->request.end_time),
            std::nullopt);
  }
  next_deadline_ = std::numeric_limits<double>::infinity();
  return timeouts_.view();
}

std::size_t TransactionMatcher::pending_count() const {
  return slots_.pending_count();
}

void TransactionMatcher::on_request(const ObservedFrame& in) {
  if (is_unanswered_broadcast(in.frame, in.check_ok)) return;
  const bool broadcast = is_broadcast_request(in.frame);
  Slot& slot = slots_[broadcast ? RequestSlots::kBroadcast : in.frame.station];
  if (slot.state == SlotState::Pending) {
    give_up(slot, TimeoutReason::NextRequestFirst, in.start_time - slot.request.end_time, in.id);
  }
  const double deadline = in.end_time + config_.timeout;
  slots_.open(slot, {in.id, in.frame, in.end_time, deadline, in.check_ok});
  next_deadline_ = std::min(next_deadline_, deadline);
}

void TransactionMatcher::on_reply(const ObservedFrame& in, FrameMatch& out) {
  if (try_answer(in, out)) return;
  if (try_duplicate(in, out)) return;
  out.unsolicited = unsolicited(in);
}

bool TransactionMatcher::try_answer(const ObservedFrame& in, FrameMatch& out) {
  const std::uint8_t station = in.frame.station;
  Slot& own = slots_[station];
  if (own.state == SlotState::Pending && answers(own.request.frame, in.frame)) {
    complete(own, in, out);
    slots_.settle(own, SlotState::Answered);
    own.answer = fits(own.request.frame, in) ? in.content : 0;
    return true;
  }
  Slot& broadcast = slots_[RequestSlots::kBroadcast];
  if (broadcast.state == SlotState::Pending && !slots_.answered_broadcast(station) &&
      answers(broadcast.request.frame, in.frame)) {
    complete(broadcast, in, out);
    slots_.note_broadcast_answer(station);
    return true;
  }
  if (in.check_ok) return false;
  Slot* only = slots_.only_pending();
  const bool rtu = detail::dialect_module(in.frame.dialect).rtu_framed;
  if (only == nullptr || slots_.is_broadcast(*only) ||
      detail::dialect_module(only->request.frame.dialect).rtu_framed != rtu) {
    return false;
  }
  complete(*only, in, out);
  slots_.settle(*only, SlotState::Answered);
  only->answer = 0;
  return true;
}

bool TransactionMatcher::try_duplicate(const ObservedFrame& in, FrameMatch& out) {
  const std::uint8_t station = in.frame.station;
  const Slot& own = slots_[station];
  const Slot& broadcast = slots_[RequestSlots::kBroadcast];
  const Slot* original = nullptr;
  if (own.state == SlotState::Answered && answers(own.request.frame, in.frame)) {
    original = &own;
  } else if (broadcast.state != SlotState::Idle && slots_.answered_broadcast(station) &&
             answers(broadcast.request.frame, in.frame)) {
    original = &broadcast;
  }
  if (original == nullptr) return false;
  // A broadcast's window keeps no reply's content: each station answers it once.
  const bool other_content = original == &own && in.content != 0 && own.answer != 0 &&
                             in.content != own.answer && fits(own.request.frame, in) &&
                             config_.timed &&
                             in.start_time - own.request.end_time <= config_.timeout;
  out.duplicate = DuplicateReply{in.id,
                                 original->request.id,
                                 in.frame.dialect,
                                 station,
                                 in.frame.function,
                                 in.check_ok,
                                 other_content,
                                 in.start_time - original->request.end_time};
  return true;
}

UnsolicitedReply TransactionMatcher::unsolicited(const ObservedFrame& in) const {
  const std::uint8_t station = in.frame.station;
  UnsolicitedReply event{in.id,       in.frame.dialect, station, in.frame.function,
                         in.check_ok, std::nullopt,     0.0};
  const Slot& own = slots_[station];
  const Slot& broadcast = slots_[RequestSlots::kBroadcast];
  const bool broadcast_closed =
      broadcast.state == SlotState::Answered || broadcast.state == SlotState::TimedOut;
  const Slot* late = nullptr;
  if (own.state == SlotState::TimedOut && answers(own.request.frame, in.frame)) {
    late = &own;
  } else if (broadcast_closed && answers(broadcast.request.frame, in.frame)) {
    late = &broadcast;
  }
  if (late != nullptr) {
    event.late_for_request_id = late->request.id;
    event.since_request = in.start_time - late->request.end_time;
  }
  return event;
}

void TransactionMatcher::complete(const Slot& slot, const ObservedFrame& reply,
                                  FrameMatch& out) const {
  const RequestSlots::RequestRecord& request = slot.request;
  const FrameSummary& r = reply.frame;
  const bool broadcast = slots_.is_broadcast(slot);
  // A damaged reply may carry a damaged station: the request says who answered it, but a
  // broadcast is answered by each station under its own address.
  const FrameSummary& who = broadcast ? r : request.frame;
  out.transaction =
      Transaction{request.id,       reply.id,      reply.start_time - request.end_time,
                  who.dialect,      who.station,   request.frame.function,
                  r.function,       reply_kind(r), broadcast,
                  request.check_ok, reply.check_ok};
  if (!reply.check_ok) return;
  const auto counts = compare_reply_count(request.frame, r);
  if (counts && !counts->matches()) {
    out.count_mismatch = ByteCountMismatch{
        request.id,       reply.id,      r.dialect,   r.station, request.frame.function,
        counts->expected, counts->found, counts->unit};
  }
}

void TransactionMatcher::give_up(Slot& slot, TimeoutReason reason, double waited,
                                 std::optional<std::uint64_t> next_request_id,
                                 std::uint8_t carrier_code) {
  // A broadcast that somebody answered has simply closed its window; it did not fail.
  if (slots_.is_broadcast(slot) && slots_.broadcast_answered()) {
    slots_.settle(slot, SlotState::Answered);
    return;
  }
  slots_.settle(slot, SlotState::TimedOut);
  const FrameSummary& f = slot.request.frame;
  timeouts_.push_back(Timeout{slot.request.id, f.dialect, f.station, f.function, reason, waited,
                              next_request_id, slot.request.check_ok, carrier_code});
}

void TransactionMatcher::expire_overdue() {
  for (Slot* slot : slots_.pending_by_deadline(true, now_)) {
    give_up(*slot, TimeoutReason::NoReply, config_.timeout, std::nullopt);
  }
  next_deadline_ = slots_.earliest_deadline();
}

}  // namespace pvtap
