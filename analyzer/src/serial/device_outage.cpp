// DeviceOutage: the doubling backoff of reopening attempts.
#include "serial/device_outage.h"

#include <algorithm>

namespace pvtap::analyzer {
namespace {

constexpr double kFirstRetry = 0.1;
constexpr double kLongestRetry = 2.0;

}  // namespace

void DeviceOutage::begin(double now) {
  since_ = now;
  backoff_ = kFirstRetry;
  next_attempt_ = now + backoff_;
}

void DeviceOutage::retry_later(double now) {
  backoff_ = std::min(backoff_ * 2, kLongestRetry);
  next_attempt_ = now + backoff_;
}

double DeviceOutage::end(double now) {
  const double seconds = now - *since_;
  since_.reset();
  return seconds;
}

}  // namespace pvtap::analyzer
