// Decides whether a frame starts at a position, and how long it is.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "pvtap/codec/dialect.h"
#include "pvtap/codec/frame_codec.h"

namespace pvtap {

// FrameCandidate: one structurally possible frame at a position (length from the header rules).
// (No member initializers: CandidateList is built once per stream position and only its
// first `size` items are ever read.)
struct FrameCandidate {
  std::size_t length;  // total bytes, check included
  Dialect dialect;
  Role role;
  // No field besides the function code can be judged (a 4-byte Modbus request, say): the
  // reading is a frame only with a good check, never a damaged frame at a pinned position.
  bool needs_good_check;
};

// CandidateList: the readings of the bytes at one position (at most a handful).
struct CandidateList {
  static constexpr std::size_t kMax = 6;  // Hybrid and Modbus share 0x11 0x16 0x17 0x18
  FrameCandidate items[kMax];
  std::size_t size = 0;
  // The smallest number of bytes needed to know the length of every reading; 0 when known.
  std::size_t need_header = 0;
  void add(const FrameCandidate& c) {
    if (size < kMax) items[size++] = c;
  }
};

// Plausibility: whether readings with implausible fields are listed.
//   Require: a count of 0 or above 125, a station outside the dialect's range, an unknown
//     exception code, ... rule the reading out (hunting for frames inside noise).
//   Ignore: only structure counts (the function code and the length fields), for a position
//     whose start is pinned, where a damaged field must not hide the frame.
enum class Plausibility : std::uint8_t { Require = 0, Ignore = 1 };

// Lists the frame readings that the header at the start of `bytes` allows: ASCII frames
// delimited by ENQ/ACK..EOT, RTU lengths from the function-code rules of each dialect. A
// reading whose length is known is listed even when `bytes` is shorter than it.
CandidateList frame_candidates(std::span<const std::uint8_t> bytes, RoleHint hint,
                               DialectSet dialects,
                               Plausibility plausibility = Plausibility::Require);

// ProbeResult: the answer of probe_frame.
struct ProbeResult {
  enum class Status : std::uint8_t {
    Complete,  // a frame of `length` bytes starts here; `check` says whether it is good
    NeedMore,  // a frame may start here; at least `more` further bytes are needed to tell
    NoFrame,   // no frame of the allowed dialects starts here
  };
  Status status = Status::NoFrame;
  std::size_t length = 0;
  std::size_t more = 0;
  Dialect dialect = kDefaultDialect;
  Role role = Role::Request;
  FrameCheck check;
};

// Probes the bytes at a position. With an unknown role every reading is tried and a good
// check decides; when every complete reading has a bad check, the one that spans exactly
// `bytes` is reported, else the first in the order request, response (expected check included).
ProbeResult probe_frame(std::span<const std::uint8_t> bytes, RoleHint hint = RoleHint::Unknown,
                        DialectSet dialects = DialectSet::all());

// Largest frame any dialect allows (ASCII reply of 255 words), an upper bound on look-ahead.
inline constexpr std::size_t kMaxFrameLength = 13 + 4 * 255;
// Largest RTU frame: a reply of 255 data bytes.
inline constexpr std::size_t kMaxRtuFrameLength = 5 + 255;
// Smallest RTU frame: a GSL exception reply.
inline constexpr std::size_t kMinRtuFrameLength = 5;

}  // namespace pvtap
