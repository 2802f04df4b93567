// SolarmanV5Reader: V5 frames found in one direction of a TCP flow, fed as segments arrive.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "pvtap/carriers/solarman_v5_frame.h"

namespace pvtap::solarman_v5 {

// Broken: a run that starts like a V5 frame (start byte, a known control code) but is none.
enum class Broken : std::uint8_t {
  Truncated,       // the bytes ended (end of flow, data lost) before the frame's end
  LengthMismatch,  // the byte where its length puts the end is not the end byte
};

// Event: a frame, a broken frame or noise, at a position of the direction's byte stream.
// Its spans are valid until the next call to the reader.
struct Event {
  enum class Kind : std::uint8_t { Frame, Broken, Noise };
  Kind kind = Kind::Noise;
  std::uint64_t offset = 0;  // stream position of its first byte
  std::span<const std::uint8_t> bytes;
  Frame frame;                        // Kind::Frame
  Broken broken = Broken::Truncated;  // Kind::Broken
  std::size_t claimed_size = 0;       // Kind::Broken: the size its header claims
};

// Totals: every byte fed is in exactly one count, or still pending.
struct Totals {
  std::uint64_t bytes_in = 0;
  std::uint64_t carrier_bytes = 0;  // V5 header, fixed payload fields and trailer
  std::uint64_t rtu_bytes = 0;      // the RTU frames inside
  std::uint64_t quirk_bytes = 0;
  std::uint64_t broken_bytes = 0;  // truncated frames and lengths that do not hold
  std::uint64_t noise_bytes = 0;   // bytes that are no V5 frame
  std::uint64_t frames = 0;
  std::uint64_t rtu_frames = 0;  // frames with an RTU frame inside
  std::uint64_t quirk_frames = 0;
  std::uint64_t stick_frames = 0;   // the stick's own frames (heartbeats, data reports, ...)
  std::uint64_t heartbeats = 0;     // of them, heartbeats
  std::uint64_t data_reports = 0;   // of them, data reports
  std::uint64_t stick_answers = 0;  // the client's answers to them (code less 0x3000)
  // Responses carrying the stick's code in place of an RTU frame; the pairing says what
  // each one answered (SolarmanV5Pairing).
  std::uint64_t stick_codes = 0;
  std::uint64_t stick_timeouts = 0;    // code 05 to a request: a timeout on the bus behind
  std::uint64_t refused_requests = 0;  // code 06 to a request naming another serial
  std::uint64_t other_codes = 0;       // any other code, or a code that answers no request
  std::uint64_t replies_after_next_request =
      0;                               // replies to a request older than the last one sent
  std::uint64_t unpaired_replies = 0;  // replies whose sequence byte echoes no request waiting
  std::uint64_t checksum_failures = 0;
  std::uint64_t truncated = 0;
  std::uint64_t length_mismatches = 0;  // broken by their length, and payloads too short
  Totals& operator+=(const Totals& o);
};

// Each start byte is tried as a frame: it holds when the byte its length points at is the
// end byte, and its checksum holds or its control code is a known one (a frame damaged in
// its checksum is still a frame). Where one does not hold, the reader resynchronises on the
// next start byte whose frame holds with a good checksum; the bytes between are a broken
// frame (when they start like one) or noise. It holds at most one frame's worth of bytes.
class SolarmanV5Reader {
 public:
  // Appends the next bytes of the stream; returns the events they complete.
  std::span<const Event> feed(std::span<const std::uint8_t> bytes);
  // Bytes were lost here: the pending bytes are decided, and nothing joins them to the next.
  std::span<const Event> discontinuity();
  // End of the stream: the pending bytes are decided.
  std::span<const Event> finish() { return discontinuity(); }

  const Totals& totals() const { return totals_; }
  std::size_t pending() const { return buffer_.size() - consumed_; }

 private:
  enum class Fit : std::uint8_t { Holds, Fails, NeedMore };
  Fit fit_at(std::size_t pos, bool strict, bool final) const;
  // Decides what it can from consumed_ on; `final`: no more bytes will come.
  void scan(bool final);
  // A start byte at consumed_ whose frame does not hold: up to the next frame that does.
  bool resync(bool final);
  void emit_frame(std::size_t size);
  void emit_run(std::size_t length, bool final);
  void count(const Event& e);
  void compact();

  std::vector<std::uint8_t> buffer_;
  std::size_t consumed_ = 0;
  std::uint64_t offset_ = 0;  // stream position of buffer_[0]
  std::vector<Event> events_;
  Totals totals_;
};

}  // namespace pvtap::solarman_v5
