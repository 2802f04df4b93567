#include "pvtap/segment_cut.h"

#include <algorithm>

#include "pvtap/framing_probe.h"

namespace pvtap {
namespace {

// The readings at one position, with the checks of the complete ones.
struct Look {
  CandidateList cands;
  FrameCheck checks[CandidateList::kMax];
  int good = -1;                // first complete reading with a good check
  bool pending = false;         // a reading, or the header, runs past the end
  std::size_t known_total = 0;  // least length of a pending reading whose length is known
  bool total_unknown = false;   // the header does not tell the length yet
};

Look look_at(std::span<const std::uint8_t> bytes, const CutOptions& o) {
  Look l;
  l.cands = frame_candidates(bytes, o.hint, o.dialects);
  if (l.cands.need_header > 0) {
    l.pending = true;
    l.total_unknown = true;
  }
  for (std::size_t i = 0; i < l.cands.size; ++i) {
    const FrameCandidate& c = l.cands.items[i];
    if (c.length > bytes.size()) {
      l.pending = true;
      if (l.known_total == 0 || c.length < l.known_total) l.known_total = c.length;
      continue;
    }
    l.checks[i] = verify_check(bytes.first(c.length), c.dialect);
    if (l.checks[i].ok && l.good < 0) l.good = static_cast<int>(i);
  }
  return l;
}

bool good_frame_at(std::span<const std::uint8_t> bytes, std::size_t at, const CutOptions& o) {
  return look_at(bytes.subspan(at), o).good >= 0;
}

// Whether a good frame starts at a position in [1, end).
bool good_frame_inside(std::span<const std::uint8_t> bytes, std::size_t end, const CutOptions& o) {
  const std::size_t limit = std::min(end, bytes.size());
  for (std::size_t q = 1; q < limit; ++q) {
    if (good_frame_at(bytes, q, o)) return true;
  }
  return false;
}

// ENQ/ACK ... EOT delimit an ASCII frame, so even a damaged one marks where noise ends.
bool has_complete_ascii(const Look& l, std::size_t size) {
  for (std::size_t i = 0; i < l.cands.size; ++i) {
    const FrameCandidate& c = l.cands.items[i];
    if (c.dialect == Dialect::Ascii && c.length <= size) return true;
  }
  return false;
}

SegmentCut frame_cut(const FrameCandidate& c, const FrameCheck& check) {
  return SegmentCut{SegmentCut::Kind::Frame, c.length, c.dialect, c.role, check};
}

SegmentCut need_more(std::size_t least_total) {
  SegmentCut cut;
  cut.kind = SegmentCut::Kind::NeedMore;
  cut.length = least_total;
  return cut;
}

enum class Evidence : std::uint8_t { Yes, No, Wait };

Evidence bad_frame_evidence(std::span<const std::uint8_t> bytes, const FrameCandidate& c,
                            const CutOptions& o) {
  if (c.dialect == Dialect::Ascii) return Evidence::Yes;
  if (good_frame_inside(bytes, c.length, o)) return Evidence::No;
  if (c.length == bytes.size()) return Evidence::Yes;
  const Look after = look_at(bytes.subspan(c.length), o);
  if (after.good >= 0) return Evidence::Yes;
  return (after.pending && o.more_may_follow) ? Evidence::Wait : Evidence::No;
}

// Noise ends where a frame may start: a good or delimited frame, or a reading that runs past
// the end. A lone last byte is not enough to end it: almost any byte may start a frame, and
// holding every noise run's last byte back would make each run wait for the next segment.
std::size_t noise_length(std::span<const std::uint8_t> bytes, const CutOptions& o) {
  for (std::size_t q = 1; q < bytes.size(); ++q) {
    const auto rest = bytes.subspan(q);
    const Look l = look_at(rest, o);
    const bool may_continue = l.pending && o.more_may_follow && rest.size() >= 2;
    if (l.good >= 0 || may_continue || has_complete_ascii(l, rest.size())) return q;
  }
  return bytes.size();
}

// The extent within which a good frame makes a pending reading implausible.
std::size_t pending_extent(const Look& l, std::size_t size) {
  const std::size_t extent = l.total_unknown ? size : l.known_total;
  return std::min(extent, kMaxFrameLength);
}

}  // namespace

SegmentCut cut_segment(std::span<const std::uint8_t> bytes, const CutOptions& options) {
  if (bytes.empty()) return SegmentCut{};
  const Look here = look_at(bytes, options);
  if (here.good >= 0) {
    const auto i = static_cast<std::size_t>(here.good);
    return frame_cut(here.cands.items[i], here.checks[i]);
  }
  if (here.pending && options.more_may_follow &&
      !good_frame_inside(bytes, pending_extent(here, bytes.size()), options)) {
    return need_more(here.total_unknown ? 0 : here.known_total);
  }
  for (std::size_t i = 0; i < here.cands.size; ++i) {
    const FrameCandidate& c = here.cands.items[i];
    if (c.length > bytes.size()) continue;
    const Evidence e = bad_frame_evidence(bytes, c, options);
    if (e == Evidence::Yes) return frame_cut(c, here.checks[i]);
    if (e == Evidence::Wait) return need_more(0);
  }
  SegmentCut noise;
  noise.length = noise_length(bytes, options);
  return noise;
}

}  // namespace pvtap
