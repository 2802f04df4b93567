// One bus seen through pieces that a caller cannot hold back (a dissector's TCP segments):
// the bus session decides, and every frame and noise run is kept by stream position.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "pvtap/session/bus_session.h"

namespace pvtap {

// BusPiece: a frame or a noise run of one direction's byte stream.
struct BusPiece {
  std::uint64_t offset = 0;  // stream position of its first byte
  std::uint32_t length = 0;
  bool frame = false;
  std::uint64_t frame_id = 0;  // the session's frame id, for frames
};

// SegmentedBus: a BusSession fed by direction and stream offset, that remembers its pieces.
//
// A dissector must say, for the bytes it was handed, which of them it shows now and from
// where it wants them again with more; later passes must show the same. The session decides
// as the stream reassembler always does (the same evidence, the same half-duplex turns as
// the analyzer's gateway flows); the pieces it decided are kept, so any later call can be
// answered from them. Pieces tile each direction's stream from 0 to decided_to(), except
// for bytes declared lost.
class SegmentedBus {
 public:
  // `outer` gets every event of the session, as a BusSession's sink would.
  SegmentedBus(BusSessionOptions options, const RegisterDecoder& decoder, BusSessionSink& outer);
  ~SegmentedBus();
  SegmentedBus(const SegmentedBus&) = delete;
  SegmentedBus& operator=(const SegmentedBus&) = delete;

  // The bytes of direction `d` that start at stream `offset`, seen at `time`. Bytes it was
  // given before are skipped; a jump forward is data lost.
  void add(Direction d, std::uint64_t offset, std::span<const std::uint8_t> bytes, double time);
  // Nothing more of this stretch of `d` can come (a datagram, a record, bytes that cannot be
  // held back): its bytes are decided now.
  void end_turn(Direction d);

  // CallSpan: the stretch of the stream one call was handed, and how far it can be shown.
  struct CallSpan {
    std::uint64_t from = 0;
    std::uint64_t shown_to = 0;  // pieces in [from, shown_to) are decided; the rest waits
    // [from, handed_to): bytes an earlier call was handed (held back then, handed again now).
    std::uint64_t handed_to = 0;
  };
  // A dissector's call: adds `bytes` (stream position `from` on), decides all of them when
  // they cannot wait for more (`can_wait` false: a datagram, a record), and says how much of
  // them is decided.
  CallSpan show(Direction d, std::uint64_t from, std::span<const std::uint8_t> bytes, double time,
                bool can_wait);

  // Stream position up to which the pieces of `d` are decided.
  std::uint64_t decided_to(Direction d) const;
  // The pieces of `d` that start in [from, to), in stream order.
  std::span<const BusPiece> pieces(Direction d, std::uint64_t from, std::uint64_t to) const;

  // The session, for its report.
  const BusSession& session() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pvtap
