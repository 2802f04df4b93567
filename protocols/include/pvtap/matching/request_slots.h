// RequestSlots: the last request of every station and of the broadcast, and what became of it.
#pragma once

#include <array>
#include <bitset>
#include <cstddef>
#include <cstdint>
#include <span>

#include "pvtap/matching/frame_summary.h"
#include "pvtap/matching/index_set.h"

namespace pvtap {

// The state table of TransactionMatcher: one slot per station address and one for the
// Hybrid broadcast (0xFF), in fixed memory. A finished request's outcome stays until the
// next request, so that repeated and late replies can still be recognized.
class RequestSlots {
 public:
  struct RequestRecord {
    std::uint64_t id = 0;
    FrameSummary frame;
    double end_time = 0;
    double deadline = 0;
    bool check_ok = true;
  };
  // Idle: never asked; Pending: waiting; Answered/TimedOut: the last request's outcome.
  enum class State : std::uint8_t { Idle, Pending, Answered, TimedOut };
  struct Slot {
    State state = State::Idle;
    RequestRecord request;
    // Answered: the content of the reply that answered it with a good check and the length it
    // asked for (0: none did).
    std::uint32_t answer = 0;
  };
  static constexpr std::size_t kBroadcast = 256;  // after the 256 stations
  static constexpr std::size_t kSlots = 257;

  Slot& operator[](std::size_t i) { return slots_[i]; }
  const Slot& operator[](std::size_t i) const { return slots_[i]; }
  bool is_broadcast(const Slot& slot) const { return &slot == &slots_[kBroadcast]; }

  // The slot waits for a reply to `request` from now on; a broadcast opens a new window that
  // nobody has answered yet.
  void open(Slot& slot, const RequestRecord& request);
  void settle(Slot& slot, State outcome);  // Pending -> Answered or TimedOut

  // Which stations answered the broadcast's current window: each may answer once.
  bool answered_broadcast(std::uint8_t station) const { return broadcast_answered_by_[station]; }
  void note_broadcast_answer(std::uint8_t station) { broadcast_answered_by_.set(station); }
  bool broadcast_answered() const { return broadcast_answered_by_.any(); }

  // A polled bus has one or two slots pending: what follows visits those only.
  std::size_t pending_count() const { return pending_.size(); }
  Slot* only_pending() { return pending_.size() == 1 ? &slots_[pending_[0]] : nullptr; }
  double earliest_deadline() const;  // infinity when none is pending
  // The pending slots (only those past their deadline at `now` when asked), oldest deadline
  // first, so that timeouts are reported in the order they fell due. Valid until the next
  // call.
  std::span<Slot* const> pending_by_deadline(bool only_overdue, double now);

 private:
  std::uint16_t index_of(const Slot& slot) const {
    return static_cast<std::uint16_t>(&slot - slots_.data());
  }

  std::array<Slot, kSlots> slots_{};
  std::bitset<256> broadcast_answered_by_;
  IndexSet<kSlots> pending_;
  std::array<Slot*, kSlots> due_{};  // scratch for ordering timeouts without allocating
};

}  // namespace pvtap
