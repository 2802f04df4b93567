#include "console/status_line.h"

#include <cstdio>

namespace pvtap::analyzer {
namespace {

constexpr double kRedrawEvery = 0.25;  // seconds

}  // namespace

void StatusLine::show(double now, const std::string& text) {
  if (!enabled_) return;
  std::fprintf(stderr, "\r\033[K%s", text.c_str());
  std::fflush(stderr);
  shown_ = true;
  next_ = now + kRedrawEvery;
}

void StatusLine::clear() {
  if (!shown_) return;
  std::fputs("\r\033[K", stderr);
  std::fflush(stderr);
  shown_ = false;
  next_ = 0;
}

}  // namespace pvtap::analyzer
