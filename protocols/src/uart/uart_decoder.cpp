// UartDecoder: bit sampling at mid-bit over runs of samples.
#include "pvtap/uart/uart_decoder.h"

#include <cmath>

namespace pvtap {

UartDecoder::UartDecoder(const UartLine& line)
    : format_(line.format),
      samples_per_bit_(line.samples_per_bit()),
      bits_(line.format.bits_per_char()) {}

void UartDecoder::begin(std::uint64_t start) {
  state_ = State::Receiving;
  current_ = UartCharacter{};
  current_.start = start;
  next_point_ = static_cast<double>(start) + samples_per_bit_ / 2;
  bit_ = 0;
  ones_ = 0;
}

void UartDecoder::feed(SampleRun run, std::vector<UartCharacter>& out) {
  const bool mark = run.level != format_.inverted;
  const std::uint64_t run_end = position_ + run.count;
  if (state_ == State::Space && mark) end_space(position_, out);
  if (state_ == State::Idle && !mark) begin(position_);
  while (state_ == State::Receiving && next_point_ < static_cast<double>(run_end)) {
    read_bit(mark, out);
  }
  position_ = run_end;
}

void UartDecoder::read_bit(bool mark, std::vector<UartCharacter>& out) {
  const unsigned parity_index = format_.data_bits + 1;
  const bool has_parity = format_.parity != Parity::None;
  if (bit_ == 0) {
    if (mark) {  // the line rose again before mid-bit: a glitch, not a start bit
      ++false_starts_;
      state_ = State::Idle;
      return;
    }
  } else if (bit_ <= format_.data_bits) {
    if (mark) current_.value |= static_cast<std::uint16_t>(1u << (bit_ - 1));
    ones_ += mark ? 1 : 0;
  } else if (has_parity && bit_ == parity_index) {
    const unsigned total = ones_ + (mark ? 1 : 0);
    current_.parity_error = (total % 2 == 0) != (format_.parity == Parity::Even);
    ones_ += mark ? 1 : 0;
  } else if (!mark) {
    current_.framing_error = true;
  }
  ++bit_;
  next_point_ += samples_per_bit_;
  if (bit_ == bits_) {
    current_.end =
        current_.start + static_cast<std::uint64_t>(std::llround(bits_ * samples_per_bit_));
    // A stop bit read as space leaves the line low: the next start needs it to rise first.
    state_ = mark ? State::Idle : State::Space;
    complete(out);
  }
}

void UartDecoder::complete(std::vector<UartCharacter>& out) {
  // All space so far may be a break: only how long the line stays low tells.
  if (state_ == State::Space && current_.value == 0 && ones_ == 0) {
    held_ = true;
    return;
  }
  out.push_back(current_);
}

void UartDecoder::end_space(std::uint64_t mark_at, std::vector<UartCharacter>& out) {
  state_ = State::Idle;
  if (!held_) return;
  held_ = false;
  const double low = static_cast<double>(mark_at - current_.start);
  if (low >= (bits_ + 1) * samples_per_bit_) {
    current_.is_break = true;
    current_.framing_error = false;
    current_.end = mark_at;
  }
  out.push_back(current_);
}

void UartDecoder::finish(std::vector<UartCharacter>& out) {
  if (state_ == State::Space) end_space(position_, out);
}

}  // namespace pvtap
