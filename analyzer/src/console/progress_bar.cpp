#include "console/progress_bar.h"

#include <algorithm>
#include <cstdio>
#include <string>

namespace pvtap::analyzer {
namespace {

constexpr int kWidth = 30;
constexpr auto kRedrawEvery = std::chrono::milliseconds(100);

}  // namespace

ProgressBar::ProgressBar(bool enabled, std::uint64_t total_bytes)
    : enabled_(enabled && total_bytes >= kMinimumBytes),
      total_(total_bytes),
      started_(std::chrono::steady_clock::now()),
      last_draw_(started_) {}

void ProgressBar::update(std::uint64_t done) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  if (now - last_draw_ < kRedrawEvery) return;
  last_draw_ = now;
  draw(done);
}

void ProgressBar::draw(std::uint64_t done) {
  const double fraction = std::min(1.0, static_cast<double>(done) / static_cast<double>(total_));
  const int filled = static_cast<int>(fraction * kWidth);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
  const double rate = seconds > 0 ? static_cast<double>(done) / seconds / 1e6 : 0.0;
  const std::string bar = std::string(static_cast<std::size_t>(filled), '#') +
                          std::string(static_cast<std::size_t>(kWidth - filled), '.');
  std::fprintf(stderr, "\r[%s] %3.0f%%  %.0f / %.0f MB  %.0f MB/s ", bar.c_str(), fraction * 100,
               static_cast<double>(done) / 1e6, static_cast<double>(total_) / 1e6, rate);
  std::fflush(stderr);
  drawn_ = true;
}

void ProgressBar::clear() {
  if (!drawn_) return;
  std::fprintf(stderr, "\r%*s\r", kWidth + 48, "");
  std::fflush(stderr);
  drawn_ = false;
}

}  // namespace pvtap::analyzer
