// FrameDecision: what starts at one stream position: a frame, noise, or "wait for bytes".
#pragma once

#include <cstdint>
#include <span>

#include "framing/chunk_timeline.h"
#include "pvtap/framing/framing_probe.h"

namespace pvtap::detail {

// RepairScan: how far the repair scan of a pinned start got before it had to wait for bytes.
// The next decision at the same position, with more bytes, goes on from there instead of
// reading again every start it already ruled out: a slow line or a gateway delivers a few bytes
// at a time, and each delivery would rescan up to a frame's length. A start ruled out stays
// ruled out: it needed no byte beyond those seen, and the timeline's silences and segment ends
// before it are fixed, as long as the timestamps are trusted or not as they were then.
struct RepairScan {
  std::uint64_t offset = UINT64_MAX;
  std::size_t resume = 1;
  bool trusted = false;
};

// DecisionInput: the buffered bytes from the position on, and what is known around them.
struct DecisionInput {
  std::span<const std::uint8_t> bytes;
  std::uint64_t offset = 0;  // stream offset of bytes[0]
  const ChunkTimeline* timeline = nullptr;
  DialectSet dialects;
  bool final = false;                 // no further bytes will follow these
  bool silence_after = false;         // trusted silence of t3.5 after the last buffered byte
  bool give_up = false;               // silent so long that no more bytes of a frame will come
  bool after_frame = false;           // the previous byte ended a frame (or input starts here)
  RepairScan* repair_scan = nullptr;  // kept by the caller between decisions; null: scan all
};

// Decision: the verdict for the position.
struct Decision {
  enum class Kind : std::uint8_t { Frame, Noise, Wait };
  Kind kind = Kind::Noise;
  FrameCandidate frame;
  FrameCheck check;
  // Noise: how many bytes from the position on are noise for certain (at least 1).
  std::size_t noise_length = 1;
};

// Structure first, plausibility second. A frame with a good check is taken at once. A frame
// with a bad check is taken only when both its ends are pinned down: its start right after a
// frame, after a proven silence (t3.5, or a batching carrier's boundary gap) or at the start
// of input; its end by a good frame right after it, a proven silence or the end of input. Nor
// may a good frame or a proven silence lie inside it (with batched timestamps, which date
// reads rather than bytes, a silence inside only when neither a good frame nor the end of
// input follows it). At a pinned start, implausible fields (a count of 0, a station out of
// range, ...) do not rule a reading out; inside noise they do. When no reading fits a pinned
// start, the bytes up to the next pinned end are read as a frame whose function code or byte
// count was damaged, if one byte set back makes its CRC match. Otherwise the first byte is
// noise: a reading that begins inside noise would turn noise into made-up frames.
Decision decide_at(const DecisionInput& in);

}  // namespace pvtap::detail
