// OutageWarnings: one warning per outage.
#include "broker/outage_warnings.h"

namespace pvtap::analyzer {

bool OutageWarnings::refused() {
  if (starting_ || refusal_reported_) return false;
  refusal_reported_ = true;
  return true;
}

bool OutageWarnings::back() {
  const bool reported = outage_reported_;
  outage_reported_ = false;
  refusal_reported_ = false;
  return reported;
}

bool OutageWarnings::lost(bool own) {
  if (own || starting_ || outage_reported_) return false;
  outage_reported_ = true;
  return true;
}

}  // namespace pvtap::analyzer
