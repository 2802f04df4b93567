#include "pvtap/matching/transaction_matcher.h"

#include <algorithm>
#include <cmath>

#include "pvtap/codec/function_codes.h"
#include "pvtap/matching/reply_rules.h"

namespace pvtap {
namespace {

bool is_broadcast_request(const FrameSummary& f) {
  return f.dialect == Dialect::Hybrid && f.station == fc::kHybridBroadcast;
}

}  // namespace

TransactionMatcher::TransactionMatcher(MatcherConfig config) : config_(config) {}

FrameMatch TransactionMatcher::on_frame(const ObservedFrame& in) {
  timeout_count_ = 0;
  move_time_to(in.start_time);
  FrameMatch out;
  out.role = in.frame.role;
  if (out.role == Role::Request && !in.role_known) {
    const Slot& own = station_slots_[in.frame.station];
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
  // The bus is busy until the frame's last byte; later timeouts are judged from there.
  now_ = std::max(now_, in.end_time);
  out.timeouts = timeouts();
  return out;
}

std::span<const Timeout> TransactionMatcher::advance(double now) {
  timeout_count_ = 0;
  move_time_to(now);
  return timeouts();
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

std::span<const Timeout> TransactionMatcher::finish() {
  timeout_count_ = 0;
  const std::size_t n = collect_pending(false);
  for (std::size_t i = 0; i < n; ++i) {
    Slot& slot = *due_[i];
    give_up(slot, TimeoutReason::CaptureEnded, std::max(0.0, now_ - slot.request.end_time),
            std::nullopt);
  }
  next_deadline_ = std::numeric_limits<double>::infinity();
  return timeouts();
}

std::size_t TransactionMatcher::pending_count() const {
  return pending_.size();
}

void TransactionMatcher::on_request(const ObservedFrame& in) {
  const bool broadcast = is_broadcast_request(in.frame);
  Slot& slot = broadcast ? broadcast_ : station_slots_[in.frame.station];
  if (slot.state == SlotState::Pending) {
    give_up(slot, TimeoutReason::NextRequestFirst, in.start_time - slot.request.end_time, in.id);
  }
  const double deadline = in.end_time + config_.timeout;
  slot.state = SlotState::Pending;
  pending_.insert(index_of(slot));
  slot.request = RequestRecord{in.id, in.frame, in.end_time, deadline, in.check_ok};
  if (broadcast) broadcast_answered_by_.reset();
  next_deadline_ = std::min(next_deadline_, deadline);
}

void TransactionMatcher::on_reply(const ObservedFrame& in, FrameMatch& out) {
  if (try_answer(in, out)) return;
  if (try_duplicate(in, out)) return;
  out.unsolicited = unsolicited(in);
}

bool TransactionMatcher::try_answer(const ObservedFrame& in, FrameMatch& out) {
  const std::uint8_t station = in.frame.station;
  Slot& own = station_slots_[station];
  if (own.state == SlotState::Pending && answers(own.request.frame, in.frame)) {
    complete(own, in, out);
    settle(own, SlotState::Answered);
    return true;
  }
  if (broadcast_.state == SlotState::Pending && !broadcast_answered_by_[station] &&
      answers(broadcast_.request.frame, in.frame)) {
    complete(broadcast_, in, out);
    broadcast_answered_by_.set(station);
    return true;
  }
  if (in.check_ok) return false;
  Slot* only = only_pending();
  const bool ascii = in.frame.dialect == Dialect::Ascii;
  if (only == nullptr || is_broadcast(*only) ||
      (only->request.frame.dialect == Dialect::Ascii) != ascii) {
    return false;
  }
  complete(*only, in, out);
  settle(*only, SlotState::Answered);
  return true;
}

TransactionMatcher::Slot* TransactionMatcher::only_pending() {
  return pending_.size() == 1 ? &slot_at(pending_[0]) : nullptr;
}

bool TransactionMatcher::try_duplicate(const ObservedFrame& in, FrameMatch& out) {
  const std::uint8_t station = in.frame.station;
  const Slot& own = station_slots_[station];
  const Slot* original = nullptr;
  if (own.state == SlotState::Answered && answers(own.request.frame, in.frame)) {
    original = &own;
  } else if (broadcast_.state != SlotState::Idle && broadcast_answered_by_[station] &&
             answers(broadcast_.request.frame, in.frame)) {
    original = &broadcast_;
  }
  if (original == nullptr) return false;
  out.duplicate = DuplicateReply{in.id,   original->request.id, in.frame.dialect,
                                 station, in.frame.function,    in.check_ok};
  return true;
}

UnsolicitedReply TransactionMatcher::unsolicited(const ObservedFrame& in) const {
  const std::uint8_t station = in.frame.station;
  UnsolicitedReply event{in.id,       in.frame.dialect, station, in.frame.function,
                         in.check_ok, std::nullopt,     0.0};
  const Slot& own = station_slots_[station];
  const bool broadcast_closed =
      broadcast_.state == SlotState::Answered || broadcast_.state == SlotState::TimedOut;
  const Slot* late = nullptr;
  if (own.state == SlotState::TimedOut && answers(own.request.frame, in.frame)) {
    late = &own;
  } else if (broadcast_closed && answers(broadcast_.request.frame, in.frame)) {
    late = &broadcast_;
  }
  if (late != nullptr) {
    event.late_for_request_id = late->request.id;
    event.since_request = in.start_time - late->request.end_time;
  }
  return event;
}

void TransactionMatcher::complete(const Slot& slot, const ObservedFrame& reply,
                                  FrameMatch& out) const {
  const RequestRecord& request = slot.request;
  const FrameSummary& r = reply.frame;
  // A damaged reply may carry a damaged station: the request says who answered it, but a
  // broadcast is answered by each station under its own address.
  const FrameSummary& who = is_broadcast(slot) ? r : request.frame;
  out.transaction =
      Transaction{request.id,       reply.id,      reply.start_time - request.end_time,
                  who.dialect,      who.station,   request.frame.function,
                  r.function,       reply_kind(r), is_broadcast(slot),
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
                                 std::optional<std::uint64_t> next_request_id) {
  // A broadcast that somebody answered has simply closed its window; it did not fail.
  if (is_broadcast(slot) && broadcast_answered_by_.any()) {
    settle(slot, SlotState::Answered);
    return;
  }
  settle(slot, SlotState::TimedOut);
  const FrameSummary& f = slot.request.frame;
  timeouts_[timeout_count_++] =
      Timeout{slot.request.id, f.dialect, f.station,       f.function,
              reason,          waited,    next_request_id, slot.request.check_ok};
}

void TransactionMatcher::expire_overdue() {
  const std::size_t n = collect_pending(true);
  for (std::size_t i = 0; i < n; ++i) {
    give_up(*due_[i], TimeoutReason::NoReply, config_.timeout, std::nullopt);
  }
  next_deadline_ = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < pending_.size(); ++k) {
    next_deadline_ = std::min(next_deadline_, slot_at(pending_[k]).request.deadline);
  }
}

// Gathers pending slots (only those past their deadline when asked) into due_, oldest first,
// so that timeouts are reported in the order they fell due.
std::size_t TransactionMatcher::collect_pending(bool only_overdue) {
  std::size_t n = 0;
  for (std::size_t k = 0; k < pending_.size(); ++k) {
    Slot& slot = slot_at(pending_[k]);
    if (only_overdue && !(slot.request.deadline < now_)) continue;
    due_[n++] = &slot;
  }
  std::sort(due_.begin(), due_.begin() + static_cast<std::ptrdiff_t>(n),
            [](const Slot* a, const Slot* b) {
              if (a->request.deadline != b->request.deadline) {
                return a->request.deadline < b->request.deadline;
              }
              return a->request.id < b->request.id;
            });
  return n;
}

void TransactionMatcher::settle(Slot& slot, SlotState outcome) {
  slot.state = outcome;
  pending_.erase(index_of(slot));
}

}  // namespace pvtap
