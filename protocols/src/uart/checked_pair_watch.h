// CheckedPairWatch: frames found at one line setting, and whether a request and its reply
// both checked (the rule that settles a passive baud search).
#pragma once

#include <cstdint>

#include "pvtap/framing/stream_reassembler.h"

namespace pvtap {

class CheckedPairWatch final : public ReassemblerSink {
 public:
  void on_frame(const FrameEvent& frame) override {
    if (!frame.check.ok) {
      last_request_ = false;
      return;
    }
    ++good_frames;
    // At a wrong rate a frame may check by chance; a reply to the station just asked, right
    // after the request, hardly ever does.
    if (frame.role == Role::Response && last_request_ && frame.bytes[0] == station_) {
      pair = true;
    }
    last_request_ = frame.role == Role::Request;
    station_ = frame.bytes[0];
  }
  void on_noise(const NoiseEvent&) override { last_request_ = false; }

  std::uint64_t good_frames = 0;
  bool pair = false;

 private:
  bool last_request_ = false;
  std::uint8_t station_ = 0;
};

}  // namespace pvtap
