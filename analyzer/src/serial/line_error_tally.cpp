// LineErrorTally: differences of the driver's counters, added up over openings.
#include "serial/line_error_tally.h"

namespace pvtap::analyzer {

bool LineErrorTally::start(const std::optional<LineErrorCounts>& counts) {
  base_ = counts;
  last_ = base_;
  if (base_) supported_ = true;
  return base_.has_value();
}

void LineErrorTally::sample(const std::optional<LineErrorCounts>& counts) {
  if (counts) last_ = counts;
}

void LineErrorTally::close() {
  if (base_ && last_) before_ = before_ + (*last_ - *base_);
  base_.reset();
  last_.reset();
}

std::optional<LineErrorCounts> LineErrorTally::total() const {
  if (!supported_) return std::nullopt;
  LineErrorCounts total = before_;
  if (base_ && last_) total = total + (*last_ - *base_);
  return total;
}

}  // namespace pvtap::analyzer
