#include "lan/lan_exchanges.h"

#include <algorithm>

namespace pvtap::sim {

std::vector<LanExchange> lan_exchanges(const BusTimeline& timeline) {
  std::vector<LanExchange> out;
  for (std::size_t i = 0; i < timeline.events.size(); ++i) {
    const BusEvent& e = timeline.events[i];
    if (e.kind != BusEvent::Kind::Frame) continue;
    if (e.role == Role::Request) {
      out.push_back({i, std::nullopt});
    } else if (!out.empty() && !out.back().reply) {
      out.back().reply = i;
    }
  }
  return out;
}

void drop_replies(BusTimeline& timeline, const std::vector<std::size_t>& replies) {
  // The request before each dropped reply becomes a timeout.
  for (const std::size_t reply : replies) {
    std::size_t r = reply;
    while (r > 0 && timeline.events[r].role != Role::Request) --r;
    const BusEvent& req = timeline.events[r];
    timeline.timeouts.push_back({req.start, req.end, req.station, req.function, {}});
  }
  std::sort(timeline.timeouts.begin(), timeline.timeouts.end(),
            [](const auto& a, const auto& b) { return a.request_start < b.request_start; });
  std::vector<BusEvent> kept;
  std::size_t next = 0;
  for (std::size_t i = 0; i < timeline.events.size(); ++i) {
    if (next < replies.size() && replies[next] == i) {
      ++next;
      continue;
    }
    kept.push_back(std::move(timeline.events[i]));
  }
  timeline.events = std::move(kept);
}

}  // namespace pvtap::sim
