#include "session/collision_tally.h"

#include <algorithm>

namespace pvtap::detail {

void CollisionTally::begin_candidate(double start, double end) {
  if (any_ && start - end_ <= t35_) {
    end_ = std::max(end_, end);
    return;
  }
  any_ = true;
  start_ = start;
  end_ = end;
  ++candidates_;
  if (second_master_) {
    named_.push_back(SessionCollision{start, end, false});
  } else if (waiting_.size() < kMaxWaiting) {
    waiting_.push_back(SessionCollision{start, end, true});
  }
  if (given_up_end_ && start >= *given_up_end_ && start - *given_up_end_ <= timeout_) {
    ++lost_;
    given_up_end_.reset();
  }
}

void CollisionTally::second_master() {
  if (second_master_) return;
  second_master_ = true;
  named_.insert(named_.end(), waiting_.begin(), waiting_.end());
  waiting_.clear();
  waiting_.shrink_to_fit();
}

void CollisionTally::add_damage(double start, double end) {
  // The same candidate when no silence of 3.5 characters lies between.
  last_request_end_.reset();
  begin_candidate(start, end);
}

// A good frame with no silence before it, after a candidate, came through it whole: the
// candidate goes on to its end.
void CollisionTally::extend_through(const SessionFrame& frame) {
  if (any_ && frame.start_time - end_ <= t35_) end_ = std::max(end_, frame.end_time);
}

void CollisionTally::add_request(const SessionFrame& request) {
  extend_through(request);
  if (last_request_end_ && request.start_time < *last_request_end_) {
    begin_candidate(request.start_time, request.end_time);
  }
  last_request_end_ = request.end_time;
}

void CollisionTally::add_other_frame(const SessionFrame& frame) {
  extend_through(frame);
  last_request_end_.reset();
}

void CollisionTally::add_timeout(const SessionTimeout& t) {
  if (t.kind != UnansweredKind::Timeout) return;
  // Overlapping the wait: a request run together with the next ends inside its candidate.
  if (any_ && end_ >= t.request_end && start_ <= t.time) {
    ++lost_;
    return;
  }
  if (t.timeout.reason == TimeoutReason::NextRequestFirst) given_up_end_ = t.request_end;
}

}  // namespace pvtap::detail
