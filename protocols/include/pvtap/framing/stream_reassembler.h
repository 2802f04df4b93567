// Turns chunks of raw bus bytes into frames and noise, accounting for every byte.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string_view>

#include "pvtap/codec/dialect.h"
#include "pvtap/codec/frame_codec.h"
#include "pvtap/framing/bus_chunk.h"

namespace pvtap {

// TimestampTrust: whether chunk timestamps are fine enough to use silent gaps as evidence.
//   Auto starts trusting and stops at the first chunk that arrived faster than the baud
//   rate allows (batched delivery by a USB adapter or a gateway).
enum class TimestampTrust : std::uint8_t { Auto = 0, Trusted = 1, Untrusted = 2 };

// FrameEvent: one frame found on the bus. `bytes` is valid only during the callback.
struct FrameEvent {
  std::uint64_t offset = 0;  // stream position of the first byte
  std::span<const std::uint8_t> bytes;
  double start_time = 0.0;     // estimated start of the first byte
  double end_time = 0.0;       // estimated end of the last byte
  double max_inner_gap = 0.0;  // longest silence inside the frame (only with trusted timing)
  Dialect dialect = kDefaultDialect;
  Role role = Role::Request;
  FrameCheck check;
};

// NoiseEvent: bytes that belong to no frame. `bytes` is valid only during the callback.
struct NoiseEvent {
  std::uint64_t offset = 0;
  std::span<const std::uint8_t> bytes;
  double start_time = 0.0;
  double end_time = 0.0;
};

// DecidedPiece: bytes whose bounds an earlier run already decided (pvtap's own capture of
// them, read again): one frame or one noise run, with the true times of its first byte's start
// and its last byte's end. `bytes` need only live for the call.
struct DecidedPiece {
  std::span<const std::uint8_t> bytes;
  double start_time = 0.0;
  double end_time = 0.0;
  Direction direction = Direction::Unknown;  // of the stream it was read from
  bool noise = false;
};

// ReassemblerSink: receives the reassembler's events in bus order.
class ReassemblerSink {
 public:
  virtual ~ReassemblerSink() = default;
  virtual void on_frame(const FrameEvent& frame) = 0;
  virtual void on_noise(const NoiseEvent& noise) = 0;
};

// ReassemblerOptions: what the reassembler recognizes and how it reads time.
struct ReassemblerOptions {
  DialectSet dialects = DialectSet::all();
  std::uint32_t baud = 9600;
  // Bits per character on the wire: 10 for 8N1, 11 with a parity bit or a second stop bit.
  unsigned bits_per_char = 10;
  TimestampTrust timestamps = TimestampTrust::Auto;
  // Live capture (idle()): how long the bus must stay silent before bytes that could still
  // begin a frame are given up as noise. A t3.5 silence already ends a frame with a bad
  // check; giving up a frame that is only missing its last bytes needs longer, because a
  // live clock reads bytes late by the OS's scheduling (a kernel worker delayed by a tick
  // leaves a silence inside a frame that was sent whole). Offline, the next bytes decide.
  double give_up_after = 0.25;
  // Batched timestamps (Untrusted, or Auto once it stopped trusting them) cannot judge t3.5,
  // but a batching carrier stamps bytes late by at most its batching interval, so a silence
  // longer than that was real and proves a frame boundary. The silence before a chunk is the
  // time since the previous chunk less the wire time of the chunk's own bytes. Seconds; < 0
  // takes a USB adapter's default latency timer plus t3.5 (kUsbLatency + t3.5); 0 never
  // proves a boundary. Gateways: their packing interval (pvtap's --gateway-gap).
  double boundary_gap = -1.0;
  static constexpr double kUsbLatency = 0.016;
  // A gateway sends a segment when the serial line went quiet (or its buffer filled): a
  // frame with a bad check whose pinned start and structure make it end exactly where a
  // segment ends is taken to end there. Never used to cut a frame that runs on: a reading
  // longer than the segment still waits for the next one.
  bool segment_ends_pin = false;
};

// ReassemblerTotals: byte accounting; bytes_in == frame_bytes + noise_bytes + pending bytes.
struct ReassemblerTotals {
  std::uint64_t bytes_in = 0;
  std::uint64_t frame_bytes = 0;
  std::uint64_t noise_bytes = 0;
  std::uint64_t frames = 0;
  std::uint64_t bad_frames = 0;
  std::uint64_t noise_runs = 0;
  ReassemblerTotals& operator+=(const ReassemblerTotals& o);  // the one way to add them up
};

// StreamReassembler: finds ASCII and RTU frames in a byte stream cut at arbitrary points.
// Structure (framing, length rules, check) decides; a silent gap of t3.5 is used only as
// evidence for where a frame with a bad check ends. A good frame is reported as soon as its
// last byte arrives; a bad one once the bytes after it (or silence) confirm its length.
class StreamReassembler {
 public:
  StreamReassembler(ReassemblerOptions options, ReassemblerSink& sink);
  ~StreamReassembler();
  StreamReassembler(const StreamReassembler&) = delete;
  StreamReassembler& operator=(const StreamReassembler&) = delete;

  void feed(const BusChunk& chunk);
  // A piece decided before: whatever was pending is decided first, then the piece is a noise
  // run as it stands, or a frame read between its pinned ends (its check decides good or
  // bad), timed as the piece says. Nothing after it joins it.
  void feed_decided(const DecidedPiece& piece);
  // The bus has been silent up to `now` (live capture); may resolve pending bytes.
  void idle(double now);
  // When idle() can next decide something: with bytes pending, the moment the silence after
  // the last byte proves a frame boundary, then the give-up time (give_up_after later).
  // nullopt when nothing is pending or no silence can decide it (offline, or batched timing
  // without a boundary gap).
  std::optional<double> next_deadline() const;
  // Bytes were lost here (capture gap, unplugged adapter): nothing may span the break.
  void discontinuity();
  // End of input: every pending byte becomes part of a frame or noise.
  void finish();

  const ReassemblerTotals& totals() const;
  std::uint64_t pending_bytes() const;
  bool timing_trusted() const;
  std::string_view timing_reason() const;  // why timing is not trusted; empty when it is

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pvtap
