// How well a stretch of samples reads in one character format: characters, line errors, and
// the frames whose check holds when the characters are framed as the bus would frame them.
#pragma once

#include <cstdint>
#include <span>

#include "pvtap/codec/dialect.h"
#include "pvtap/uart/uart_decoder.h"

namespace pvtap {

// FormatTrial: what reading the stretch in one format gave.
struct FormatTrial {
  UartFormat format;
  std::uint64_t characters = 0;
  std::uint64_t line_errors = 0;  // framing and parity errors
  std::uint64_t good_frames = 0;  // frames of any dialect whose check holds
  // Of those, the ones the framing read as requests and as replies: which side of a bus a
  // channel carrying one direction is.
  std::uint64_t requests = 0, responses = 0;
  unsigned distinct_values = 0;  // how many byte values the characters took

  // Line errors on the characters of the good frames: a format that reads the frames' values
  // right but not their bits (an 8E1 line read as 8N2, its parity bit taken for a stop bit).
  std::uint64_t frame_line_errors = 0;

  // More good frames first, then fewer line errors inside them. Where frames read alike and
  // clean, the characters between them (a driver's glitches, noise) do not choose: the
  // earlier candidate stays. Without frames, fewer line errors.
  bool better_than(const FormatTrial& other) const {
    if (good_frames != other.good_frames) return good_frames > other.good_frames;
    if (frame_line_errors != other.frame_line_errors)
      return frame_line_errors < other.frame_line_errors;
    if (good_frames > 0) return false;
    return line_errors < other.line_errors;
  }
};

FormatTrial try_format(const UartLine& line, std::span<const SampleRun> runs,
                       DialectSet dialects = DialectSet::all());

}  // namespace pvtap
