// Pairs requests with replies on one bus and reports what did not pair.
#pragma once

#include <array>
#include <bitset>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>

#include "pvtap/matching/frame_summary.h"
#include "pvtap/matching/match_events.h"

namespace pvtap {

// MatcherConfig: how long a request may wait for its reply.
struct MatcherConfig {
  double timeout = 1.0;  // seconds from the request's end to the reply's start; must be > 0
};

// ObservedFrame: one frame as the reassembler saw it on the bus.
struct ObservedFrame {
  std::uint64_t id = 0;  // the caller's sequence number, echoed in every event
  FrameSummary frame;
  double start_time = 0;  // when the first byte began, seconds
  double end_time = 0;    // when the last byte ended, seconds
  bool check_ok = true;
  // The caller knows who sent the frame (e.g. separate taps per direction), so its role is
  // never corrected.
  bool role_known = false;
};

// IndexSet: a set of indices below N with constant-time insert and erase, iterated in no
// particular order; used to visit only the requests that wait instead of every address.
template <std::size_t N>
class IndexSet {
 public:
  void insert(std::uint16_t i) {
    if (contains(i)) return;
    position_[i] = static_cast<std::uint16_t>(size_);
    members_[size_++] = i;
  }
  void erase(std::uint16_t i) {
    if (!contains(i)) return;
    const std::uint16_t last = members_[--size_];
    members_[position_[i]] = last;
    position_[last] = position_[i];
  }
  bool contains(std::uint16_t i) const {
    return position_[i] < size_ && members_[position_[i]] == i;
  }
  std::size_t size() const { return size_; }
  std::uint16_t operator[](std::size_t k) const { return members_[k]; }

 private:
  std::array<std::uint16_t, N> members_{};
  std::array<std::uint16_t, N> position_{};
  std::size_t size_ = 0;
};

// TransactionMatcher: pairs requests with replies and returns, as values, the timeouts,
// unsolicited and duplicate replies, length mismatches and corrected roles it decided.
//
// Frames must arrive in bus order. Each frame first advances time to its start_time (which
// times out the requests whose timeout has passed), then is handled. Pairing is by station:
// each station has at most one pending request, and a new request to a station gives up the
// previous one (NextRequestFirst). A reply answers the pending request of its own station;
// failing that, the pending Hybrid broadcast (0xFF). The broadcast stays open until its
// timeout or the next broadcast, and every station that answers it in that window makes one
// transaction; a broadcast that nobody answered times out with station 0xFF. A reply with a
// bad check whose station or function does not fit (the damaged byte may be that one)
// answers the one pending request when exactly one is pending: the slave answered and the
// line damaged the answer, which is not a timeout.
//
// What one frame decided comes back as a FrameMatch (see there for the order). Lengths are
// judged only on replies with a good check: in a corrupted reply the length field itself may
// be the corrupted part.
//
// Memory is fixed (one record per address plus the broadcast, and the timeouts of one call);
// nothing is allocated per frame. The timeouts returned stay valid until the next call.
class TransactionMatcher {
 public:
  explicit TransactionMatcher(MatcherConfig config = {});

  // Handles one frame: its role (corrected when it is a GSL 0x06 echo) and what it decided.
  FrameMatch on_frame(const ObservedFrame& frame);

  // Moves time forward while the bus is silent (live capture): the requests that timed out.
  std::span<const Timeout> advance(double now);

  // The earliest moment advance() reports a timeout, or later (a wake that finds nothing
  // due sets the next one); nullopt when no request waits.
  std::optional<double> next_deadline() const;

  // Ends the capture: every request still waiting times out with CaptureEnded.
  std::span<const Timeout> finish();

  // Requests waiting for a reply (broadcast included), for diagnostics.
  std::size_t pending_count() const;

 private:
  struct RequestRecord {
    std::uint64_t id = 0;
    FrameSummary frame;
    double end_time = 0;
    double deadline = 0;
    bool check_ok = true;
  };
  // Idle: never asked; Pending: waiting; Answered/TimedOut: the last request's outcome, kept
  // until the next request so that repeated and late replies can be recognized.
  enum class SlotState : std::uint8_t { Idle, Pending, Answered, TimedOut };
  struct Slot {
    SlotState state = SlotState::Idle;
    RequestRecord request;
  };
  static constexpr std::size_t kSlots = 257;  // 256 stations + the broadcast

  void on_request(const ObservedFrame& in);
  void on_reply(const ObservedFrame& in, FrameMatch& out);
  bool try_answer(const ObservedFrame& in, FrameMatch& out);
  Slot* only_pending();
  bool try_duplicate(const ObservedFrame& in, FrameMatch& out);
  UnsolicitedReply unsolicited(const ObservedFrame& in) const;
  void complete(const Slot& slot, const ObservedFrame& reply, FrameMatch& out) const;
  void give_up(Slot& slot, TimeoutReason reason, double waited,
               std::optional<std::uint64_t> next_request_id);
  void settle(Slot& slot, SlotState outcome);  // Pending -> Answered or TimedOut
  void move_time_to(double now);
  void expire_overdue();
  std::span<const Timeout> timeouts() const { return {timeouts_.data(), timeout_count_}; }
  std::size_t collect_pending(bool only_overdue);
  bool is_broadcast(const Slot& slot) const { return &slot == &broadcast_; }
  Slot& slot_at(std::size_t i) {
    return i < station_slots_.size() ? station_slots_[i] : broadcast_;
  }
  std::uint16_t index_of(const Slot& slot) const {
    return is_broadcast(slot) ? static_cast<std::uint16_t>(station_slots_.size())
                              : static_cast<std::uint16_t>(&slot - station_slots_.data());
  }

  MatcherConfig config_;
  std::array<Slot, 256> station_slots_{};
  Slot broadcast_;
  std::bitset<256> broadcast_answered_by_;
  // The slots in state Pending: a polled bus has one or two, and the per-frame deadline work
  // visits those only.
  IndexSet<kSlots> pending_;
  double now_ = -std::numeric_limits<double>::infinity();
  // A lower bound on the earliest deadline; stale-early is harmless (one extra scan).
  double next_deadline_ = std::numeric_limits<double>::infinity();
  std::array<Slot*, kSlots> due_{};  // scratch for ordering timeouts without allocating
  // The timeouts of the current call: at most one per slot, since each was pending.
  std::array<Timeout, kSlots> timeouts_{};
  std::size_t timeout_count_ = 0;
};

}  // namespace pvtap
