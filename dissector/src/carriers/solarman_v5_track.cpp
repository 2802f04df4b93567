#include "carriers/solarman_v5_track.h"

#include <algorithm>
#include <memory>

namespace pvtap::dissector {
namespace {

std::vector<std::unique_ptr<SolarmanV5Track>> g_tracks;

}  // namespace

SegmentedBus::CallSpan SolarmanV5Track::show(Direction d, std::uint64_t from,
                                             std::span<const std::uint8_t> bytes, bool can_wait) {
  Side& s = sides_[index_of(d)];
  const std::uint64_t end = from + bytes.size();
  const std::uint64_t handed_to = std::clamp(s.fed_to, from, end);
  if (from > s.fed_to) {
    keep(s, s.reader.discontinuity());
    s.shift += from - s.fed_to;
    s.fed_to = from;
  }
  if (end > s.fed_to) {
    keep(s, s.reader.feed(bytes.subspan(s.fed_to - from)));
    s.fed_to = end;
  }
  if (!can_wait) keep(s, s.reader.discontinuity());
  const std::uint64_t decided = s.fed_to - s.reader.pending();
  return SegmentedBus::CallSpan{from, std::clamp(decided, from, end), handed_to};
}

void SolarmanV5Track::keep(Side& s, std::span<const solarman_v5::Event> events) {
  for (const solarman_v5::Event& e : events) {
    s.pieces.push_back(V5Piece{e.offset + s.shift, static_cast<std::uint32_t>(e.bytes.size()),
                               e.kind, e.broken, static_cast<std::uint32_t>(e.claimed_size)});
  }
}

std::span<const V5Piece> SolarmanV5Track::pieces(Direction d, std::uint64_t from,
                                                 std::uint64_t to) const {
  const std::vector<V5Piece>& all = sides_[index_of(d)].pieces;
  const auto by_offset = [](const V5Piece& p, std::uint64_t o) { return p.offset < o; };
  const auto first = std::lower_bound(all.begin(), all.end(), from, by_offset);
  const auto last = std::lower_bound(first, all.end(), to, by_offset);
  return {all.data() + (first - all.begin()), static_cast<std::size_t>(last - first)};
}

SolarmanV5Track* new_v5_track(BusTrack& rtu) {
  g_tracks.push_back(std::make_unique<SolarmanV5Track>(rtu));
  return g_tracks.back().get();
}

void release_v5_tracks() {
  g_tracks.clear();
}

}  // namespace pvtap::dissector
