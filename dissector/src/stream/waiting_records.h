// WaitingRecords: serial records whose last byte the bus has not decided yet.
#pragma once

#include <cstdint>
#include <deque>

namespace pvtap::dissector {

struct CallView;

// A record whose bytes wait shows no piece of them; the record whose call later decides its
// last byte shows that piece, and the waiting record points to it (as TCP's segments of a
// reassembled PDU do). First pass only: records come in stream order, so their ends grow and
// the oldest is completed first.
class WaitingRecords {
 public:
  // The record of `view`, whose bytes end at stream position `end`, waits.
  void add(std::uint64_t end, CallView* view) { waiting_.push_back({end, view}); }

  // Calls `complete(view)` for every waiting record whose last byte lies before `decided_to`,
  // oldest first, and forgets them.
  template <typename Complete>
  void complete(std::uint64_t decided_to, Complete&& complete) {
    while (!waiting_.empty() && waiting_.front().end <= decided_to) {
      complete(*waiting_.front().view);
      waiting_.pop_front();
    }
  }

 private:
  struct Waiting {
    std::uint64_t end;
    CallView* view;
  };
  std::deque<Waiting> waiting_;
};

}  // namespace pvtap::dissector
