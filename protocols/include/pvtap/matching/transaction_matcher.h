// Pairs requests with replies on one bus and reports what did not pair.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>

#include "pvtap/matching/frame_summary.h"
#include "pvtap/matching/match_events.h"
#include "pvtap/matching/request_slots.h"
#include "pvtap/matching/timeout_list.h"

namespace pvtap {

// MatcherConfig: how long a request may wait for its reply, and how soon a copy of it is an
// echo.
struct MatcherConfig {
  double timeout = 1.0;  // seconds from the request's end to the reply's start; must be > 0
  // A request that repeats the one before it byte for byte and starts within this many
  // seconds of its end is an echo (EchoedRequest): no device answers that soon (a Modbus
  // slave keeps 3.5 characters of silence), so it is the tap's adapter. nullopt: no echoes
  // (an input without timestamps cannot tell one from a master's quick retry).
  std::optional<double> echo_within;
  // The same for a function whose reply is the request's bytes again (a single write): an
  // echo comes back at once, while a slave that answers too early still leaves a character or
  // two: one character time at the bus's baud.
  double echoing_reply_within = 0;
  // A second reply with other contents is an address conflict only where time shows it
  // answered the same request: within `timeout` of the request's end. Without timestamps it
  // may as well answer a request the capture lost, and stays a duplicate.
  bool timed = true;
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
  // The carrier paired this reply with its station's pending request (Modbus/TCP, by
  // transaction id): however late it comes, time does not give that request up first.
  bool answers_pending = false;
  // What the frame's bytes were, in brief: its check and length (two frames alike in both
  // carry the same bytes, bar a chance in 65,536). 0: not known.
  std::uint32_t content = 0;
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
// An echo of a request (MatcherConfig::echo_within) leaves the request pending, as if it had
// ended with its echo: the slave answers after the last copy on the line.
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

  // The carrier answered the pending request of `station` with `code` in place of a reply:
  // no reply came from the bus (CarrierNoReply); nothing when none is pending.
  std::span<const Timeout> carrier_no_reply(std::uint8_t station, double now, std::uint8_t code);

  // Ends the capture: every request still waiting times out with CaptureEnded.
  std::span<const Timeout> finish();

  // Requests waiting for a reply (broadcast included), for diagnostics.
  std::size_t pending_count() const;

 private:
  using Slot = RequestSlots::Slot;
  using SlotState = RequestSlots::State;

  // The last frame when it was a request with a good check, for telling its echo.
  struct LastRequest {
    bool open = false;
    std::uint64_t id = 0;
    std::uint8_t station = 0;
    std::uint32_t content = 0;
    double end_time = 0;
  };

  bool is_echo(const ObservedFrame& in) const;
  void take_echo(const ObservedFrame& in, FrameMatch& out);
  void on_request(const ObservedFrame& in);
  void on_reply(const ObservedFrame& in, FrameMatch& out);
  bool try_answer(const ObservedFrame& in, FrameMatch& out);
  bool try_duplicate(const ObservedFrame& in, FrameMatch& out);
  UnsolicitedReply unsolicited(const ObservedFrame& in) const;
  void complete(const Slot& slot, const ObservedFrame& reply, FrameMatch& out) const;
  void give_up(Slot& slot, TimeoutReason reason, double waited,
               std::optional<std::uint64_t> next_request_id, std::uint8_t carrier_code = 0);
  void move_time_to(double now);
  void keep_waiting_for(const ObservedFrame& reply);
  void expire_overdue();

  MatcherConfig config_;
  RequestSlots slots_;
  double now_ = -std::numeric_limits<double>::infinity();
  // A lower bound on the earliest deadline; stale-early is harmless (one extra scan).
  double next_deadline_ = std::numeric_limits<double>::infinity();
  TimeoutList timeouts_;  // those of the current call
  LastRequest last_request_;
};

}  // namespace pvtap
