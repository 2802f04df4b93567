#include "outputs/bus_bytes.h"

namespace pvtap::sim {

std::vector<TimedByte> bus_bytes(const BusTimeline& timeline) {
  std::vector<TimedByte> out;
  for (const BusEvent& e : timeline.events) {
    const auto n = static_cast<Micros>(e.bytes.size());
    for (Micros i = 0; i < n; ++i) {
      // Byte i has fully arrived (i + 1) character times after the first one started.
      const Micros t = e.start + (e.end - e.start) * (i + 1) / n;
      out.push_back({t, e.bytes[static_cast<std::size_t>(i)], e.role});
    }
  }
  return out;
}

}  // namespace pvtap::sim
