// PublishSchedule: the interval's next tick, and the replay's window.
#include "mqtt/publish_schedule.h"

namespace pvtap::analyzer {
namespace {

// Messages a replay lets be on their way before it waits.
constexpr std::size_t kReplayWindow = 500;

}  // namespace

bool PublishSchedule::due(double now) {
  if (next_ == 0) next_ = now + interval_;
  if (now < next_) return false;
  next_ = now + interval_;
  return true;
}

void PublishSchedule::pace(MqttClient& client) const {
  if (!live_) client.wait_for_room(kReplayWindow);
}

}  // namespace pvtap::analyzer
