// SolarmanV5Track: one conversation's V5 frames as the core's reader finds them, kept by stream
// position so that every pass shows what the first decided, and the bus of the RTU frames.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "pvtap/carriers/solarman_v5_reader.h"
#include "pvtap/session/segmented_bus.h"
#include "stream/bus_track.h"

namespace pvtap::dissector {

// V5Piece: a frame, broken frame or noise run of one direction's byte stream.
struct V5Piece {
  std::uint64_t offset = 0;
  std::uint32_t length = 0;
  solarman_v5::Event::Kind kind = solarman_v5::Event::Kind::Noise;
  solarman_v5::Broken broken = solarman_v5::Broken::Truncated;
  std::uint32_t claimed_size = 0;
};

class SolarmanV5Track {
 public:
  explicit SolarmanV5Track(BusTrack& rtu) : rtu_(rtu) {}

  // A call's bytes of `d` from stream position `from` (bytes fed before are skipped, a jump
  // forward is data lost); all decided when they cannot wait for more. As SegmentedBus::show.
  SegmentedBus::CallSpan show(Direction d, std::uint64_t from, std::span<const std::uint8_t> bytes,
                              bool can_wait);
  // The pieces of `d` that start in [from, to), in stream order.
  std::span<const V5Piece> pieces(Direction d, std::uint64_t from, std::uint64_t to) const;
  // The bus the RTU frames go to (its stream offsets also serve the TCP sequence numbers).
  BusTrack& rtu() { return rtu_; }

 private:
  struct Side {
    solarman_v5::SolarmanV5Reader reader;
    std::uint64_t fed_to = 0;
    std::uint64_t shift = 0;  // stream position less reader position: the bytes lost
    std::vector<V5Piece> pieces;
  };
  void keep(Side& s, std::span<const solarman_v5::Event> events);

  BusTrack& rtu_;
  std::array<Side, kDirections> sides_;
};

// A track that lives until the capture file is closed, with its RTU bus.
SolarmanV5Track* new_v5_track(BusTrack& rtu);
// Frees every track; registered as a cleanup routine.
void release_v5_tracks();

}  // namespace pvtap::dissector
