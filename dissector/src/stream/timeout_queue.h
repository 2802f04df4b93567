// TimeoutQueue: requests whose timeout a session reported, waiting for a packet to announce them.
#pragma once

#include <vector>

#include "plan/frame_record.h"

namespace pvtap::dissector {

class TimeoutQueue {
 public:
  void add(FrameRecord* request) { waiting_.push_back(request); }

  // The requests whose own packet is known, taken out; a request not shown yet waits, since
  // its announcement names its packet.
  std::vector<FrameRecord*> take_shown() {
    std::vector<FrameRecord*> ready;
    std::erase_if(waiting_, [&](FrameRecord* r) {
      if (r->packet == 0) return false;
      ready.push_back(r);
      return true;
    });
    return ready;
  }

 private:
  std::vector<FrameRecord*> waiting_;
};

}  // namespace pvtap::dissector
