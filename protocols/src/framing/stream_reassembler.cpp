#include "pvtap/framing/stream_reassembler.h"

#include <algorithm>
#include <cstdint>
#include <vector>

#include "framing/chunk_timeline.h"
#include "framing/frame_decision.h"

namespace pvtap {
namespace {

// Noise is reported in runs; a run this long is reported even before it ends, so a bus
// full of garbage never grows the buffer.
constexpr std::size_t kMaxNoiseRun = 4096;
// A decision never needs more than a frame and the frame after it; past that it is forced.
constexpr std::size_t kMaxLookahead = 2 * kMaxFrameLength + 16;
// Consumed bytes are dropped from the buffer front once they pass this size.
constexpr std::size_t kCompactThreshold = 64 * 1024;

}  // namespace

struct StreamReassembler::Impl {
  Impl(ReassemblerOptions o, ReassemblerSink& s)
      : options(o),
        sink(s),
        timeline(BusTiming(o.baud, o.bits_per_char), o.timestamps, resolved_boundary_gap(o),
                 o.segment_ends_pin) {}

  static double resolved_boundary_gap(const ReassemblerOptions& o) {
    if (o.boundary_gap >= 0) return o.boundary_gap;
    return ReassemblerOptions::kUsbLatency + BusTiming(o.baud, o.bits_per_char).t35;
  }

  ReassemblerOptions options;
  ReassemblerSink& sink;
  detail::ChunkTimeline timeline;
  ReassemblerTotals totals;
  // Undecided bytes kept between feeds. Decisions read `data`: the buffer, or the caller's
  // chunk itself when nothing was pending (then only its undecided tail is copied).
  std::vector<std::uint8_t> buffer;
  std::span<const std::uint8_t> data;
  std::uint64_t buffer_offset = 0;  // stream offset of data[0]
  std::size_t head = 0;             // first undecided byte
  std::size_t noise_begin = 0;      // pending noise run is [noise_begin, head)
  bool silence_after = false;
  bool give_up = false;     // see ReassemblerOptions::give_up_after
  bool after_frame = true;  // input starts here: as good a frame boundary as a frame's end
  detail::RepairScan repair_scan;
  // The piece being fed by feed_decided, whose times replace the timeline's when a frame or
  // noise run spans all of it.
  const DecidedPiece* decided = nullptr;

  std::uint64_t offset_of(std::size_t index) const { return buffer_offset + index; }
  bool nothing_pending() const { return head == buffer.size() && noise_begin == head; }

  void compact() {
    if (noise_begin < kCompactThreshold || noise_begin * 2 < buffer.size()) return;
    buffer.erase(buffer.begin(), buffer.begin() + static_cast<std::ptrdiff_t>(noise_begin));
    buffer_offset += noise_begin;
    head -= noise_begin;
    noise_begin = 0;
  }

  // Decides inside the caller's chunk, then keeps the undecided tail (pending noise included).
  void process_in_place(std::span<const std::uint8_t> chunk) {
    data = chunk;
    process(false);
    buffer.assign(chunk.begin() + static_cast<std::ptrdiff_t>(noise_begin), chunk.end());
    buffer_offset += noise_begin;
    head -= noise_begin;
    noise_begin = 0;
    data = buffer;
  }

  void flush_noise() {
    if (noise_begin == head) return;
    NoiseEvent e;
    e.offset = offset_of(noise_begin);
    e.bytes = data.subspan(noise_begin, head - noise_begin);
    const auto times = timeline.span_times(e.offset, offset_of(head - 1));
    e.start_time = times.start;
    e.end_time = times.end;
    if (decided != nullptr && e.bytes.size() == decided->bytes.size()) {
      e.start_time = decided->start_time;
      e.end_time = decided->end_time;
    }
    totals.noise_bytes += e.bytes.size();
    ++totals.noise_runs;
    sink.on_noise(e);
    noise_begin = head;
  }

  void emit_frame(const detail::Decision& d) {
    flush_noise();
    FrameEvent e;
    e.offset = offset_of(head);
    e.bytes = data.subspan(head, d.frame.length);
    const std::uint64_t last = e.offset + d.frame.length - 1;
    const auto times = timeline.span_times(e.offset, last);
    e.start_time = times.start;
    e.end_time = times.end;
    e.max_inner_gap = times.max_gap;
    if (decided != nullptr && d.frame.length == decided->bytes.size()) {
      e.start_time = decided->start_time;
      e.end_time = decided->end_time;
    }
    e.dialect = d.frame.dialect;
    e.role = d.frame.role;
    e.check = d.check;
    totals.frame_bytes += d.frame.length;
    ++totals.frames;
    if (!d.check.ok) ++totals.bad_frames;
    sink.on_frame(e);
    head += d.frame.length;
    noise_begin = head;
  }

  // Decides position after position until the bytes run out or a decision must wait.
  void process(bool final, std::size_t stop = SIZE_MAX) {
    detail::DecisionInput in;
    in.timeline = &timeline;
    in.dialects = options.dialects;
    in.silence_after = silence_after;
    in.give_up = give_up;
    in.repair_scan = &repair_scan;
    while (head < data.size() && head < stop) {
      in.bytes = data.subspan(head);
      in.offset = offset_of(head);
      in.final = final || in.bytes.size() > kMaxLookahead;
      in.after_frame = after_frame;
      const detail::Decision d = detail::decide_at(in);
      if (d.kind == detail::Decision::Kind::Wait) break;
      after_frame = d.kind == detail::Decision::Kind::Frame;
      if (after_frame) {
        emit_frame(d);
      } else {
        // Noise runs stay within kMaxNoiseRun even when a decision names several bytes.
        head += std::min(d.noise_length, kMaxNoiseRun - (head - noise_begin));
        if (head - noise_begin >= kMaxNoiseRun) flush_noise();
      }
    }
    if (final) flush_noise();
    timeline.drop_before(offset_of(noise_begin));
  }

  void reset_buffer() {
    buffer_offset += buffer.size();
    buffer.clear();
    data = buffer;
    head = noise_begin = 0;
  }
};

StreamReassembler::StreamReassembler(ReassemblerOptions options, ReassemblerSink& sink)
    : impl_(std::make_unique<Impl>(options, sink)) {}

StreamReassembler::~StreamReassembler() = default;

void StreamReassembler::feed(const BusChunk& chunk) {
  if (chunk.bytes.empty()) return;
  Impl& m = *impl_;
  m.totals.bytes_in += chunk.bytes.size();
  // A silence before this chunk was already judged; decisions now see the new bytes.
  m.silence_after = false;
  m.give_up = false;
  const bool small = chunk.bytes.size() <= kMaxLookahead;
  if (m.noise_begin == m.buffer.size() && !small) {
    // Everything before was decided and reported: no copy unless a tail stays undecided.
    m.reset_buffer();
    m.timeline.add(m.offset_of(chunk.bytes.size()), chunk.bytes.size(), chunk.time,
                   chunk.direction);
    m.process_in_place(chunk.bytes);
    return;
  }
  m.compact();
  // A small chunk (a gateway's segment) is cheaper to copy than to decide in place.
  if (small) {
    m.buffer.insert(m.buffer.end(), chunk.bytes.begin(), chunk.bytes.end());
    m.data = m.buffer;
    m.timeline.add(m.offset_of(m.buffer.size()), chunk.bytes.size(), chunk.time, chunk.direction);
    m.process(false);
    return;
  }
  // The pending tail is decided with just enough of the chunk behind it for any decision
  // (more than kMaxLookahead bytes force it as the whole chunk would); once decisions pass
  // into the chunk with no noise run open, the rest is decided in place.
  const std::size_t tail_end = m.buffer.size();
  const std::size_t window = std::min(chunk.bytes.size(), kMaxLookahead + 1);
  const auto window_end = chunk.bytes.begin() + static_cast<std::ptrdiff_t>(window);
  m.buffer.insert(m.buffer.end(), chunk.bytes.begin(), window_end);
  m.data = m.buffer;
  m.timeline.add(m.offset_of(tail_end + chunk.bytes.size()), chunk.bytes.size(), chunk.time,
                 chunk.direction);
  m.process(false, tail_end);
  if (m.head >= tail_end && m.noise_begin >= tail_end) {
    m.buffer_offset += tail_end;
    m.head -= tail_end;
    m.noise_begin -= tail_end;
    m.process_in_place(chunk.bytes);
    return;
  }
  m.buffer.insert(m.buffer.end(), window_end, chunk.bytes.end());
  m.data = m.buffer;
  m.process(false);
}

void StreamReassembler::feed_decided(const DecidedPiece& piece) {
  if (piece.bytes.empty()) return;
  Impl& m = *impl_;
  if (!m.nothing_pending()) m.process(true);
  m.reset_buffer();
  m.totals.bytes_in += piece.bytes.size();
  m.silence_after = false;
  m.give_up = false;
  m.timeline.add(m.offset_of(piece.bytes.size()), piece.bytes.size(), piece.end_time,
                 piece.direction);
  m.decided = &piece;
  m.data = piece.bytes;
  if (piece.noise) {
    m.head = piece.bytes.size();
    m.flush_noise();
  } else {
    m.after_frame = true;  // its writer decided a frame starts here
    m.process(true);
  }
  m.decided = nullptr;
  m.timeline.drop_before(m.offset_of(piece.bytes.size()));
  m.buffer_offset += piece.bytes.size();
  m.head = m.noise_begin = 0;
  m.data = m.buffer;
  m.after_frame = true;  // and one ends where it ends
}

void StreamReassembler::idle(double now) {
  Impl& m = *impl_;
  if (m.nothing_pending()) return;
  if (!m.timeline.silent_since_last_byte(now)) return;
  m.silence_after = true;
  m.give_up = m.timeline.silent_since_last_byte(now - m.options.give_up_after);
  m.process(false);
  // Noise ends where the silence begins: report it now rather than with the next frame.
  if (m.head == m.buffer.size()) m.flush_noise();
}

std::optional<double> StreamReassembler::next_deadline() const {
  const Impl& m = *impl_;
  // Once the bytes were given up, no longer silence decides anything more.
  if (m.nothing_pending() || m.give_up) return std::nullopt;
  return m.timeline.silence_proven_at(m.silence_after ? m.options.give_up_after : 0.0);
}

void StreamReassembler::discontinuity() {
  Impl& m = *impl_;
  m.process(true);
  m.reset_buffer();
  m.timeline.break_continuity();
  m.after_frame = true;  // what follows lost data starts afresh
}

void StreamReassembler::finish() {
  Impl& m = *impl_;
  m.process(true);
  m.reset_buffer();
}

const ReassemblerTotals& StreamReassembler::totals() const {
  return impl_->totals;
}

std::uint64_t StreamReassembler::pending_bytes() const {
  return impl_->buffer.size() - impl_->noise_begin;
}

bool StreamReassembler::timing_trusted() const {
  return impl_->timeline.trusted();
}

std::string_view StreamReassembler::timing_reason() const {
  return impl_->timeline.reason();
}

}  // namespace pvtap
