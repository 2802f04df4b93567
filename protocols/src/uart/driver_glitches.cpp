#include "pvtap/uart/driver_glitches.h"

#include <cstdint>

#include "pvtap/codec/checksums.h"

namespace pvtap {
namespace {

// A run this long is no frame waiting for its end: its head is given out.
constexpr std::size_t kLongestRun = 600;

bool suspect(const UartCharacter& c) {
  return c.framing_error || c.value == 0x00 || c.value == 0xFE || c.value == 0xFF;
}

// Whether characters [first, last] end in the CRC-16/MODBUS of the ones before.
bool checks(const std::vector<UartCharacter>& run, std::size_t first, std::size_t last) {
  if (last < first + 3 || last >= run.size()) return false;
  std::uint8_t bytes[kLongestRun];
  std::size_t n = 0;
  for (std::size_t i = first; i <= last; ++i) bytes[n++] = static_cast<std::uint8_t>(run[i].value);
  const std::uint16_t crc = Crc16Modbus::compute(std::span(bytes, n - 2));
  return bytes[n - 2] == (crc & 0xFF) && bytes[n - 1] == (crc >> 8);
}

// Samples from one character's end to the next one's start; negative where a character starts
// before the one before was due to end (a glitch right on a stop bit, a clock running fast).
double silence(const UartCharacter& before, const UartCharacter& after) {
  return static_cast<double>(after.start) - static_cast<double>(before.end);
}

}  // namespace

DriverGlitchFilter::DriverGlitchFilter(const UartLine& line)
    : char_samples_(line.samples_per_bit() * line.format.bits_per_char()) {}

bool DriverGlitchFilter::switch_on_glitch(std::size_t first, std::size_t last) const {
  const UartCharacter& c = run_[first];
  if (!head_open_ || last <= first || !suspect(c)) return false;
  if (silence(c, run_[first + 1]) > 1.5 * char_samples_) return false;
  return c.framing_error || c.parity_error ||
         (checks(run_, first + 1, last) && !checks(run_, first, last));
}

bool DriverGlitchFilter::switch_off_glitch(std::size_t first, std::size_t last) const {
  const UartCharacter& c = run_[last];
  if (last <= first || !suspect(c)) return false;
  if (silence(run_[last - 1], c) > 1.5 * char_samples_) return false;
  return c.framing_error || c.parity_error ||
         (checks(run_, first, last - 1) && !checks(run_, first, last));
}

void DriverGlitchFilter::close_run(std::vector<UartCharacter>& out,
                                   std::vector<DriverGlitch>& glitches) {
  std::size_t first = 0, last = run_.size() - 1;
  const bool on = switch_on_glitch(first, last);
  if (on) glitches.push_back({run_[first++], true});
  const bool off = switch_off_glitch(first, last);
  for (std::size_t i = first; i < last + (off ? 0 : 1); ++i) out.push_back(run_[i]);
  if (off) glitches.push_back({run_[last], false});
  run_.clear();
  head_open_ = true;
}

void DriverGlitchFilter::feed(const UartCharacter& c, std::vector<UartCharacter>& out,
                              std::vector<DriverGlitch>& glitches) {
  if (!run_.empty() && silence(run_.back(), c) >= 3.5 * char_samples_) close_run(out, glitches);
  if (run_.size() + 1 >= kLongestRun) {
    // Not a frame: everything but the newest character goes, the head no longer a glitch.
    if (head_open_ && switch_on_glitch(0, run_.size() - 1)) {
      glitches.push_back({run_.front(), true});
      run_.erase(run_.begin());
    }
    out.insert(out.end(), run_.begin(), run_.end() - 1);
    run_.erase(run_.begin(), run_.end() - 1);
    head_open_ = false;
  }
  run_.push_back(c);
}

void DriverGlitchFilter::flush(std::vector<UartCharacter>& out,
                               std::vector<DriverGlitch>& glitches) {
  if (!run_.empty()) close_run(out, glitches);
}

}  // namespace pvtap
