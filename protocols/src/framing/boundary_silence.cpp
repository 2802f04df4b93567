#include "framing/boundary_silence.h"

namespace pvtap::detail {

BoundarySilence::BoundarySilence(const BusTiming& timing, TimestampTrust trust, double boundary_gap)
    : timing_(timing),
      mode_(trust),
      boundary_gap_(boundary_gap),
      trusted_(trust != TimestampTrust::Untrusted) {
  if (trust == TimestampTrust::Untrusted) reason_ = "timestamps declared too coarse by the source";
}

std::optional<double> BoundarySilence::shortest() const {
  if (trusted_) return timing_.t35 - kGapToleranceChars * timing_.char_time;
  if (boundary_gap_ > 0) return boundary_gap_;
  return std::nullopt;
}

void BoundarySilence::distrust(std::string_view why) {
  if (mode_ != TimestampTrust::Auto || !trusted_) return;
  trusted_ = false;
  reason_ = why;
}

}  // namespace pvtap::detail
