#include "bus/bus_wire.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace pvtap::sim {

Micros BusWire::char_time(std::size_t bytes) const {
  // 10 bits per character: start, 8 data, stop.
  return static_cast<Micros>(std::llround(static_cast<double>(bytes) * 1e7 / baud_));
}

Micros BusWire::put(BusEvent event, Micros at) {
  event.start = at;
  event.end = at + char_time(event.bytes.size());
  event.master = master_;
  event.exchange = exchange_;
  const Micros end = event.end;
  const bool echoed = echo_ && event.kind == BusEvent::Kind::Frame && event.role == Role::Request;
  events_.push_back(std::move(event));
  if (!echoed) return end;
  // The adapter hands the request back as it goes out; the tap records it after the request.
  BusEvent copy = events_.back();
  copy.fault = "echo";
  copy.start = end;
  copy.end = end + (end - at);
  events_.push_back(std::move(copy));
  return events_.back().end;
}

// Collisions. RS485 has no dominant level (CAN has one): where two drivers drive opposite
// levels at once, the differential voltage at a receiver falls near 0 V, inside the +-200 mV a
// receiver needs, and the bus's fail-safe bias reads it as idle (mark, a 1 bit). Where both
// drive the same level, that level is read. So neither talker wins: the line carries the
// bitwise OR of the two, taken here character by character on the first talker's grid (the
// second's characters are shifted to it), from the first one's first byte to the last one's
// last byte. Every receiver reads that garbage: the slave asked ignores it, the master waiting
// for a reply gets none and waits out its timeout. Both frames are lost, and the rest of both
// exchanges never happens (a slave answers only a request it heard whole).
std::optional<Overlap> BusWire::collide(std::size_t first) {
  if (first >= events_.size()) return std::nullopt;
  const std::uint8_t fresh_master = events_[first].master;
  std::optional<std::pair<std::size_t, std::size_t>> hit;  // (older, fresh)
  Micros hit_at = 0;
  for (std::size_t f = first; f < events_.size(); ++f) {
    for (std::size_t o = 0; o < first; ++o) {
      const BusEvent& a = events_[o];
      const BusEvent& b = events_[f];
      if (a.master == fresh_master || a.end <= b.start || b.end <= a.start) continue;
      if (a.fault == "echo" || b.fault == "echo") continue;  // the tap's copy, not on the line
      const Micros at = std::max(a.start, b.start);
      if (!hit || at < hit_at) {
        hit = {o, f};
        hit_at = at;
      }
    }
  }
  if (!hit) return std::nullopt;
  Overlap out;
  out.older = events_[hit->first];
  out.fresh = events_[hit->second];
  const BusEvent& lead = out.older.start <= out.fresh.start ? out.older : out.fresh;
  const BusEvent& late = out.older.start <= out.fresh.start ? out.fresh : out.older;
  const auto shift = static_cast<std::size_t>(std::llround(
      static_cast<double>(late.start - lead.start) / static_cast<double>(char_time(1))));
  std::vector<std::uint8_t> garbage(std::max(lead.bytes.size(), shift + late.bytes.size()), 0);
  for (std::size_t i = 0; i < lead.bytes.size(); ++i) garbage[i] = lead.bytes[i];
  for (std::size_t i = 0; i < late.bytes.size(); ++i)
    garbage[shift + i] = static_cast<std::uint8_t>(garbage[shift + i] | late.bytes[i]);
  out.start = lead.start;
  out.end = std::max(lead.end, late.end);
  // Both transmissions go, with whatever followed them in their exchanges.
  const auto gone = [&](const BusEvent& e) {
    return (e.exchange == out.older.exchange && e.start >= out.older.start) ||
           (e.exchange == out.fresh.exchange && e.start >= out.fresh.start);
  };
  std::erase_if(events_, gone);
  BusEvent line;
  line.kind = BusEvent::Kind::Noise;
  line.role = Role::Response;
  line.fault = "collision";
  line.bytes = std::move(garbage);
  line.master = out.fresh.master;
  line.exchange = out.fresh.exchange;
  line.start = out.start;
  line.end = out.end;
  events_.push_back(std::move(line));
  return out;
}

void BusWire::sort_by_time() {
  std::stable_sort(events_.begin(), events_.end(),
                   [](const BusEvent& a, const BusEvent& b) { return a.start < b.start; });
}

Micros BusWire::put_noise(Micros at, SimRandom& random) {
  BusEvent noise;
  noise.kind = BusEvent::Kind::Noise;
  noise.role = Role::Response;
  noise.fault = "noise";
  // High bytes (0xA0-0xFE): no function code, and above the stations of the usual buses,
  // so the noise is not mistaken for the start of a frame.
  const auto n = random.between(3, 12);
  while (noise.bytes.size() < static_cast<std::size_t>(n)) {
    const auto b = static_cast<std::uint8_t>(random.between(0xA0, 0xFE));
    noise.bytes.push_back(b);
  }
  return put(std::move(noise), at);
}

// A reader can delimit a damaged frame only where both its ends are pinned, so damage goes
// only where the start is: a request right after a frame (never noise), a reply (which follows
// its own request) never after noise from the slave side either, as a gateway's reply stream
// has no request in between. What follows pins the end: the master's timeout after a request,
// a pause after a reply. Asked before the poll's request is on the bus.
bool BusWire::may_damage(Role role) const {
  if (role == Role::Request)
    return !events_.empty() && events_.back().kind == BusEvent::Kind::Frame;
  for (auto it = events_.rbegin(); it != events_.rend(); ++it)
    if (it->role == Role::Response) return it->kind == BusEvent::Kind::Frame;
  return true;
}

}  // namespace pvtap::sim
