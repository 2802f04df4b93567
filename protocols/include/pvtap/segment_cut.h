// Names what starts at the first byte of a buffer (frame, noise or "need more"), without time.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "pvtap/dialect.h"
#include "pvtap/frame_codec.h"

namespace pvtap {

// SegmentCut: the verdict for the first byte of a buffer.
struct SegmentCut {
  enum class Kind : std::uint8_t {
    Frame,     // a frame of `length` bytes; `check` says whether it is good
    Noise,     // `length` bytes that belong to no frame
    NeedMore,  // a frame may start here; `length` is the least total it needs, 0 when unknown
  };
  Kind kind = Kind::Noise;
  std::size_t length = 0;
  Dialect dialect = Dialect::Gsl;
  Role role = Role::Request;
  FrameCheck check;
};

// CutOptions: what the caller knows about the bytes.
struct CutOptions {
  RoleHint hint = RoleHint::Unknown;  // who sent them (one direction of a TCP stream)
  DialectSet dialects = DialectSet::all();
  bool more_may_follow = true;  // false: the buffer is all there is (a datagram, a record)
};

// Cuts the buffer at its first byte, for callers that see a stream piecewise with no usable
// timestamps (Wireshark's TCP reassembly) and must name each piece's length before they go on.
//
// The rules follow the stream reassembler's, with "the end of the buffer" in place of silence:
//   1. a reading with a good check is a frame at once;
//   2. a reading that runs past the end waits for more bytes (NeedMore), unless a good frame
//      starts later in the buffer: a real frame rarely holds one, noise often precedes one;
//   3. a reading with a bad check is a frame when no good frame starts inside it and its end
//      is pinned: by the end of the buffer, or by a good frame right after it (ASCII frames
//      are pinned by their delimiters);
//   4. otherwise the bytes up to the next place where a frame may start are noise, so that
//      noise never swallows a frame that follows it.
SegmentCut cut_segment(std::span<const std::uint8_t> bytes, const CutOptions& options);

}  // namespace pvtap
