// LineErrorTally: the line errors of one serial device while pvtap listened, over all its
// openings.
#pragma once

#include <optional>

#include "report/live_report.h"

namespace pvtap::analyzer {

// The driver's counters are cumulative per port and start again when an adapter is plugged in
// again: each opening counts from its first reading, and what an opening counted is kept when
// the device goes away.
class LineErrorTally {
 public:
  // The device was opened and its counters read (nullopt: the driver keeps none). False when
  // it keeps none.
  bool start(const std::optional<LineErrorCounts>& counts);
  // Since the device was opened, with counters.
  bool counting() const { return base_.has_value(); }
  // A later reading; nullopt (a failed one) keeps the last.
  void sample(const std::optional<LineErrorCounts>& counts);
  // The device is closed.
  void close();
  // Over every opening; nullopt when the driver never gave counters.
  std::optional<LineErrorCounts> total() const;

 private:
  std::optional<LineErrorCounts> base_;
  std::optional<LineErrorCounts> last_;
  LineErrorCounts before_;  // of earlier openings (before unplugs)
  bool supported_ = false;
};

}  // namespace pvtap::analyzer
