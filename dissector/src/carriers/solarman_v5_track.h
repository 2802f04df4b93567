// SolarmanV5Track: one conversation's V5 frames as the core's reader finds them, kept by stream
// position so that every pass shows what the first decided, and the bus of their RTU frames,
// paired by the sequence byte the stick echoes as pvtap audit pairs them.
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <map>
#include <span>
#include <utility>
#include <vector>

#include "plan/frame_record.h"
#include "pvtap/carriers/solarman_v5_pairing.h"
#include "pvtap/carriers/solarman_v5_reader.h"
#include "pvtap/session/bus_session.h"
#include "pvtap/session/segmented_bus.h"
#include "stream/bus_track.h"
#include "stream/station_names.h"
#include "stream/timeout_queue.h"

namespace pvtap::dissector {

// RtuPiece: what the bus made of part of a V5 frame's RTU bytes: a frame (its record) or noise.
struct RtuPiece {
  std::uint32_t offset = 0;  // in the RTU bytes
  std::uint32_t length = 0;
  FrameRecord* record = nullptr;  // null: noise
};

// V5Rtu: the RTU bytes of one V5 request or response. Until the pairing hands them to the bus
// (a request waits for its response), `own` says what the frame says of itself.
struct V5Rtu {
  FrameRecord* own = nullptr;
  std::vector<RtuPiece> pieces;  // empty until the bus decided them
  // A request naming a serial other than the stick's: no bus frame until the stick says
  // (it may refuse it, and then it never is one).
  bool other_serial = false;
  bool refused = false;  // the stick refused it (code 06): it never reached the bus
};

// V5Piece: a frame, broken frame or noise run of one direction's byte stream.
struct V5Piece {
  std::uint64_t offset = 0;
  std::uint32_t length = 0;
  solarman_v5::Event::Kind kind = solarman_v5::Event::Kind::Noise;
  solarman_v5::Broken broken = solarman_v5::Broken::Truncated;
  std::uint32_t claimed_size = 0;
  V5Rtu* rtu = nullptr;  // requests and responses with an RTU frame
  // Responses with a stick code: what the pairing made of it, and the serial a refused
  // request named.
  solarman_v5::Release::Kind code_meaning = solarman_v5::Release::Kind::Code;
  std::uint32_t addressed_serial = 0;
};

class SolarmanV5Track final : solarman_v5::ReleaseSink, BusSessionSink {
 public:
  // `offsets`: the conversation's bus track, whose TCP sequence numbers give stream positions.
  SolarmanV5Track(BusTrack& offsets, const ProtocolSettings& settings);

  // A call's bytes of `d` from stream position `from`, seen at `time` (bytes fed before are
  // skipped, a jump forward is data lost); all decided when they cannot wait for more. As
  // SegmentedBus::show.
  SegmentedBus::CallSpan show(Direction d, std::uint64_t from, std::span<const std::uint8_t> bytes,
                              double time, bool can_wait);
  // The pieces of `d` that start in [from, to), in stream order.
  std::span<const V5Piece> pieces(Direction d, std::uint64_t from, std::uint64_t to) const;
  // The bus track whose stream offsets serve the TCP sequence numbers.
  BusTrack& offsets() { return offsets_; }
  // The requests whose timeout the session reported, for the packet that announces them.
  TimeoutQueue& timeouts() { return timeouts_; }

 private:
  struct Side {
    solarman_v5::SolarmanV5Reader reader;
    std::uint64_t fed_to = 0;
    std::uint64_t shift = 0;  // stream position less reader position: the bytes lost
    std::vector<V5Piece> pieces;
    std::uint64_t rtu_fed = 0;  // RTU bytes fed to the session: its stream positions
  };
  void keep(Direction d, std::span<const solarman_v5::Event> events, double time);
  void release(const solarman_v5::Release& r) override;
  void on_frame(const SessionFrame& f) override;
  void on_noise(const SessionNoise& n) override;
  void on_timeout(const SessionTimeout& t) override;
  V5Piece* piece_at(Direction d, std::uint64_t offset);

  BusTrack& offsets_;
  BusSession session_;
  solarman_v5::SolarmanV5Pairing pairing_;
  std::array<Side, kDirections> sides_;
  std::deque<V5Rtu> rtus_;  // stable addresses for the pieces
  // The RTU bytes being fed to the session, and their first stream position there.
  V5Rtu* feeding_ = nullptr;
  std::uint64_t feeding_from_ = 0;
  bool bus_started_ = false;  // a frame reached the session (pvtap audit's bus exists)
  std::vector<FrameRecord*> by_id_;
  TimeoutQueue timeouts_;
  StationNames names_;
  // The dialect each station's good frames spoke last, plus one (0: none yet).
  std::array<std::uint8_t, 256> station_dialects_{};
};

// A track that lives until the capture file is closed.
SolarmanV5Track* new_v5_track(BusTrack& offsets, const ProtocolSettings& settings);
// Frees every track; registered as a cleanup routine.
void release_v5_tracks();

}  // namespace pvtap::dissector
