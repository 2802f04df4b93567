#include "pvtap/matching/frame_summary.h"

namespace pvtap {

FrameSummary summarize(const Frame& frame) {
  FrameSummary s;
  static_cast<FrameHeader&>(s) = frame;
  s.word_count = static_cast<std::uint16_t>(frame.words.size());
  if (!frame.words.empty()) s.first_word = frame.words[0];
  // A diagnostics echo repeats its sub-function where other echoes repeat their address.
  if (frame.sub_function) s.start = frame.sub_function;
  return s;
}

}  // namespace pvtap
