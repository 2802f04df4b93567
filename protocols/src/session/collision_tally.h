// CollisionTally: the traces two transmissions at once leave on a bus, and the requests they cost.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "pvtap/session/bus_session.h"

namespace pvtap::detail {

// Where two talkers drive the line at once (RS485 has no dominant level), every receiver reads
// garbage from the first one's first byte to the last one's last: bytes that belong to no
// frame, or a frame with a bad check, with now and then a frame whose bytes came through
// whole; where the second starts just before the first ends, two requests that overlap. Each
// stretch of such traces without 3.5 characters of silence in it is one candidate. Only a bus
// with two or more masters has collisions: on a bus of one master the same traces are line
// damage. So candidates wait until the session sees a second master (second_master()); from
// then on, each is named as it begins. Named candidates are taken with take_named().
//
// A request is lost in a collision when its reply was due while one happened: a candidate
// overlapped the time from the request's end to its giving up, or, for a request given up because
// the next one to its station came first (another master's, on a shared bus), within --timeout of
// its end.
class CollisionTally {
 public:
  CollisionTally(double t35, double timeout) : t35_(t35), timeout_(timeout) {}

  // A noise run or a frame with a bad check, from `start` to `end` (seconds).
  void add_damage(double start, double end);
  // Each good request: one beginning before the previous good request ended, with no frame
  // between (echoes are not passed here), is a candidate.
  void add_request(const SessionFrame& request);
  // Each good reply.
  void add_other_frame(const SessionFrame& frame);
  void add_timeout(const SessionTimeout& t);

  // The bus has a second master: the candidates so far are collisions, and so is every later
  // one.
  void second_master();
  bool has_second_master() const { return second_master_; }
  // Candidates seen while the bus showed one master.
  bool waiting() const { return candidates_ > 0 && !second_master_; }
  // The collisions named since the last call, in order.
  template <typename Take>
  void take_named(Take take) {
    for (const SessionCollision& c : named_) take(c);
    named_.clear();
  }

  // Collisions and the requests lost in them; none on a bus of one master.
  std::uint64_t collisions() const { return second_master_ ? candidates_ : 0; }
  std::uint64_t lost_requests() const { return second_master_ ? lost_ : 0; }

 private:
  // Candidates of a bus that shows one master are kept up to this many to be named later
  // (counted beyond it): enough for any shared bus before its evidence, bounded on a bus of
  // one master and much damage.
  static constexpr std::size_t kMaxWaiting = 4096;

  void begin_candidate(double start, double end);
  void extend_through(const SessionFrame& frame);

  double t35_;
  double timeout_;
  std::uint64_t candidates_ = 0;
  std::uint64_t lost_ = 0;
  bool second_master_ = false;
  std::vector<SessionCollision> waiting_;  // candidates before the second master showed
  std::vector<SessionCollision> named_;    // not taken yet
  bool any_ = false;
  double start_ = 0;  // the last candidate's
  double end_ = 0;
  std::optional<double> last_request_end_;
  // The last request given up for the next request to its station, until a candidate counts it.
  std::optional<double> given_up_end_;
};

}  // namespace pvtap::detail
