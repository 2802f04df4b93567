#include "pvtap/matching/frame_summary.h"

namespace pvtap {

FrameSummary summarize(const Frame& frame) {
  FrameSummary s;
  s.dialect = frame.dialect;
  s.role = frame.role;
  s.station = frame.station;
  s.function = frame.function;
  s.start = frame.start;
  s.count = frame.count;
  s.byte_count = frame.byte_count;
  s.word_count = static_cast<std::uint16_t>(frame.words.size());
  if (!frame.words.empty()) s.first_word = frame.words[0];
  return s;
}

}  // namespace pvtap
