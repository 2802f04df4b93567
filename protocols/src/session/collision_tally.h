// CollisionTally: the traces two transmissions at once leave on a bus, and the requests they cost.
#pragma once

#include <cstdint>
#include <optional>

#include "pvtap/session/bus_session.h"

namespace pvtap::detail {

// Where two talkers drive the line at once (RS485 has no dominant level), every receiver reads
// garbage from the first one's first byte to the last one's last: bytes that belong to no
// frame, or a frame with a bad check, with now and then a frame whose bytes came through
// whole; where the second starts just before the first ends, two requests that overlap. Each
// stretch of such traces without 3.5 characters of silence in it is one candidate. Only a bus with two or more masters has
// collisions (BusSession::report): on a bus of one master the same traces are line damage.
//
// A request is lost in a collision when its reply was due while one happened: a candidate
// overlapped the time from the request's end to its giving up, or, for a request given up because the next one
// to its station came first (another master's, on a shared bus), within --timeout of its end.
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

  std::uint64_t candidates() const { return candidates_; }
  std::uint64_t lost_requests() const { return lost_; }

 private:
  void begin_candidate(double start, double end);
  void extend_through(const SessionFrame& frame);

  double t35_;
  double timeout_;
  std::uint64_t candidates_ = 0;
  std::uint64_t lost_ = 0;
  bool any_ = false;
  double start_ = 0;  // the last candidate's
  double end_ = 0;
  std::optional<double> last_request_end_;
  // The last request given up for the next request to its station, until a candidate counts it.
  std::optional<double> given_up_end_;
};

}  // namespace pvtap::detail
