// SolarmanV5Reader: framing by start byte, length, end byte and checksum; resynchronisation.
#include "pvtap/carriers/solarman_v5_reader.h"

#include <algorithm>

namespace pvtap::solarman_v5 {
namespace {

constexpr std::uint64_t one_if(bool b) {
  return b ? 1u : 0u;
}

}  // namespace

Totals& Totals::operator+=(const Totals& o) {
  bytes_in += o.bytes_in;
  carrier_bytes += o.carrier_bytes;
  rtu_bytes += o.rtu_bytes;
  quirk_bytes += o.quirk_bytes;
  broken_bytes += o.broken_bytes;
  noise_bytes += o.noise_bytes;
  frames += o.frames;
  rtu_frames += o.rtu_frames;
  quirk_frames += o.quirk_frames;
  stick_frames += o.stick_frames;
  stick_answers += o.stick_answers;
  heartbeats += o.heartbeats;
  data_reports += o.data_reports;
  stick_codes += o.stick_codes;
  stick_timeouts += o.stick_timeouts;
  refused_requests += o.refused_requests;
  other_codes += o.other_codes;
  replies_after_next_request += o.replies_after_next_request;
  unpaired_replies += o.unpaired_replies;
  checksum_failures += o.checksum_failures;
  truncated += o.truncated;
  length_mismatches += o.length_mismatches;
  return *this;
}

std::span<const Event> SolarmanV5Reader::feed(std::span<const std::uint8_t> bytes) {
  compact();
  buffer_.insert(buffer_.end(), bytes.begin(), bytes.end());
  totals_.bytes_in += bytes.size();
  scan(false);
  return events_;
}

std::span<const Event> SolarmanV5Reader::discontinuity() {
  compact();
  scan(true);
  return events_;
}

// Drops the bytes decided by earlier calls; their events' spans are no longer used.
void SolarmanV5Reader::compact() {
  events_.clear();
  buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(consumed_));
  offset_ += consumed_;
  consumed_ = 0;
}

SolarmanV5Reader::Fit SolarmanV5Reader::fit_at(std::size_t pos, bool strict, bool final) const {
  const std::size_t available = buffer_.size() - pos;
  if (available < kHeaderSize) return final ? Fit::Fails : Fit::NeedMore;
  const std::span<const std::uint8_t> at(buffer_.data() + pos, available);
  const Header h = read_header(at);
  if (h.length > kMaxPayload) return Fit::Fails;
  const std::size_t size = kOverhead + h.length;
  if (available < size) return final ? Fit::Fails : Fit::NeedMore;
  if (at[size - 1] != kEnd) return Fit::Fails;
  const bool sum_ok = at[size - kTrailerSize] == checksum_of(at.first(size));
  // Resynchronising inside damaged bytes asks for both; a frame where the last one ended
  // needs one of them.
  const bool known = known_control(h.control);
  const bool holds = strict ? sum_ok && known : sum_ok || known;
  return holds ? Fit::Holds : Fit::Fails;
}

void SolarmanV5Reader::scan(bool final) {
  while (consumed_ < buffer_.size()) {
    if (buffer_[consumed_] != kStart) {
      // No frame starts before the next start byte.
      const auto next = std::find(buffer_.begin() + static_cast<std::ptrdiff_t>(consumed_) + 1,
                                  buffer_.end(), kStart);
      emit_run(static_cast<std::size_t>(next - buffer_.begin()) - consumed_, final);
      continue;
    }
    const Fit fit = fit_at(consumed_, false, final);
    if (fit == Fit::NeedMore) return;
    if (fit == Fit::Holds) {
      emit_frame(kOverhead + read_header({buffer_.data() + consumed_, kHeaderSize}).length);
    } else if (!resync(final)) {
      return;
    }
  }
}

bool SolarmanV5Reader::resync(bool final) {
  for (std::size_t q = consumed_ + 1; q < buffer_.size(); ++q) {
    if (buffer_[q] != kStart) continue;
    const Fit fit = fit_at(q, true, final);
    if (fit == Fit::NeedMore) {
      // Whether q holds a frame decides only where the run before it ends. Once more than a
      // frame's worth waits, the run up to q is given as it is, so that the reader never
      // holds more than the frame at q (tests/corpus/solarman_v5_reader/crash-run-before-
      // an-unfinished-frame).
      if (buffer_.size() - consumed_ <= kOverhead + kMaxPayload) return false;
      emit_run(q - consumed_, true);
      return true;
    }
    if (fit == Fit::Holds) {
      emit_run(q - consumed_, true);
      return true;
    }
  }
  if (!final && buffer_.size() - consumed_ < kOverhead + kMaxPayload) return false;
  emit_run(buffer_.size() - consumed_, true);
  return true;
}

void SolarmanV5Reader::emit_frame(std::size_t size) {
  Event e;
  e.kind = Event::Kind::Frame;
  e.offset = offset_ + consumed_;
  e.bytes = {buffer_.data() + consumed_, size};
  e.frame = parse_frame(e.bytes);
  consumed_ += size;
  count(e);
  events_.push_back(e);
}

// A run that is no frame: broken when it starts like one, else noise. `decided`: the run
// ends where a frame starts or the bytes end, so it can be judged whole.
void SolarmanV5Reader::emit_run(std::size_t length, bool decided) {
  Event e;
  e.offset = offset_ + consumed_;
  e.bytes = {buffer_.data() + consumed_, length};
  e.kind = Event::Kind::Noise;
  if (decided && length >= 5 && e.bytes[0] == kStart) {
    const std::uint16_t code = static_cast<std::uint16_t>(e.bytes[3] | (e.bytes[4] << 8));
    const std::size_t claimed =
        kOverhead + static_cast<std::size_t>(e.bytes[1] | (e.bytes[2] << 8));
    if (known_control(code)) {
      e.kind = Event::Kind::Broken;
      e.claimed_size = claimed;
      // Truncated when the bytes ended before the end its length claims; else the byte
      // there was no end byte, or the length is beyond any frame's.
      const bool cut = claimed <= kOverhead + kMaxPayload && consumed_ + claimed > buffer_.size();
      e.broken = cut ? Broken::Truncated : Broken::LengthMismatch;
    }
  }
  consumed_ += length;
  count(e);
  events_.push_back(e);
}

void SolarmanV5Reader::count(const Event& e) {
  switch (e.kind) {
    case Event::Kind::Noise:
      totals_.noise_bytes += e.bytes.size();
      return;
    case Event::Kind::Broken:
      totals_.broken_bytes += e.bytes.size();
      ++(e.broken == Broken::Truncated ? totals_.truncated : totals_.length_mismatches);
      return;
    case Event::Kind::Frame:
      break;
  }
  const Frame& f = e.frame;
  ++totals_.frames;
  totals_.carrier_bytes += f.carrier_bytes();
  totals_.rtu_bytes += f.rtu_length;
  totals_.quirk_bytes += f.quirk_bytes;
  totals_.rtu_frames += one_if(f.rtu_length > 0);
  totals_.quirk_frames += one_if(f.quirk_bytes > 0);
  totals_.checksum_failures += one_if(!f.checksum_ok());
  totals_.length_mismatches += one_if(f.payload_short);
  const bool stick = f.kind == FrameKind::StickFrame;
  totals_.stick_frames += one_if(stick);
  totals_.stick_answers += one_if(f.kind == FrameKind::StickReply);
  totals_.heartbeats += one_if(stick && f.header.control == control::kHeartbeat);
  totals_.data_reports += one_if(stick && f.header.control == control::kDataReport);
  totals_.stick_codes += one_if(f.stick_code.has_value());
}

}  // namespace pvtap::solarman_v5
