// ProgressBar: how far through its input a long audit is, drawn on stderr when it is a terminal.
#pragma once

#include <chrono>
#include <cstdint>

namespace pvtap::analyzer {

class ProgressBar {
 public:
  // Inputs smaller than this finish before a bar would help.
  static constexpr std::uint64_t kMinimumBytes = 8 << 20;

  ProgressBar(bool enabled, std::uint64_t total_bytes);
  ~ProgressBar() { clear(); }
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  // `done` bytes of the input are read; redraws at most ten times a second.
  void update(std::uint64_t done);
  // Removes the bar, so that the report starts on a clean line.
  void clear();
  bool active() const { return enabled_; }

 private:
  void draw(std::uint64_t done);

  bool enabled_;
  bool drawn_ = false;
  std::uint64_t total_;
  std::chrono::steady_clock::time_point started_;
  std::chrono::steady_clock::time_point last_draw_;
};

}  // namespace pvtap::analyzer
