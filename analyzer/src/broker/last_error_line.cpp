// LastErrorLine: kept under its own lock.
#include "broker/last_error_line.h"

namespace pvtap::analyzer {

void LastErrorLine::keep(const char* text) {
  std::lock_guard lock(mutex_);
  text_ = text;
}

std::string LastErrorLine::detail() {
  std::lock_guard lock(mutex_);
  return text_.empty() ? std::string() : " (" + text_ + ")";
}

}  // namespace pvtap::analyzer
