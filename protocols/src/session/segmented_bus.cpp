#include "pvtap/session/segmented_bus.h"

#include <algorithm>

namespace pvtap {
struct SegmentedBus::Impl : BusSessionSink {
  Impl(BusSessionOptions o, const RegisterDecoder& decoder, BusSessionSink& outer_sink)
      : outer(outer_sink), session(o, decoder, *this) {}

  // StreamPieces: what one direction's stream was cut into, and how far it was fed.
  struct StreamPieces {
    std::vector<BusPiece> pieces;
    std::uint64_t fed_to = 0;
    std::uint64_t decided_to = 0;
  };

  void on_frame(const SessionFrame& f) override {
    record(f.direction, BusPiece{f.offset, static_cast<std::uint32_t>(f.bytes.size()), true, f.id});
    outer.on_frame(f);
  }
  void on_noise(const SessionNoise& n) override {
    record(n.direction,
           BusPiece{n.noise.offset, static_cast<std::uint32_t>(n.noise.bytes.size()), false, 0});
    outer.on_noise(n);
  }
  void on_timeout(const SessionTimeout& t) override { outer.on_timeout(t); }
  void on_gap(const SessionGap& g) override { outer.on_gap(g); }
  void on_collision(const SessionCollision& c) override { outer.on_collision(c); }

  void record(Direction d, const BusPiece& p) {
    StreamPieces& s = streams[index_of(d)];
    // The session counts each direction's offsets from its last restart; this stream's own
    // positions continue across losses, so the piece is placed after what was decided.
    BusPiece placed = p;
    placed.offset = p.offset + base[index_of(d)];
    s.pieces.push_back(placed);
    s.decided_to = placed.offset + placed.length;
  }

  BusSessionSink& outer;
  BusSession session;
  std::array<StreamPieces, kDirections> streams{};
  // Where the session's offsets of a direction start in this object's stream positions:
  // after a loss the session's reassembler numbers its bytes on without the lost ones.
  std::array<std::uint64_t, kDirections> base{};
};

SegmentedBus::SegmentedBus(BusSessionOptions options, const RegisterDecoder& decoder,
                           BusSessionSink& outer)
    : impl_(std::make_unique<Impl>(options, decoder, outer)) {}

SegmentedBus::~SegmentedBus() = default;

void SegmentedBus::add(Direction d, std::uint64_t offset, std::span<const std::uint8_t> bytes,
                       double time) {
  Impl& m = *impl_;
  Impl::StreamPieces& s = m.streams[index_of(d)];
  const std::uint64_t end = offset + bytes.size();
  if (end <= s.fed_to) return;
  if (offset > s.fed_to) {
    m.session.data_lost(d, time, offset - s.fed_to);
    // Everything before the loss is decided now; the lost bytes belong to no piece.
    m.base[index_of(d)] += offset - s.fed_to;
    s.decided_to = offset;
    s.fed_to = offset;
  }
  const auto fresh = bytes.subspan(static_cast<std::size_t>(s.fed_to - offset));
  s.fed_to = end;
  m.session.feed(BusChunk{fresh, time, d});
}

SegmentedBus::CallSpan SegmentedBus::show(Direction d, std::uint64_t from,
                                          std::span<const std::uint8_t> bytes, double time,
                                          bool can_wait) {
  const std::uint64_t end = from + bytes.size();
  const std::uint64_t handed_to = std::clamp(impl_->streams[index_of(d)].fed_to, from, end);
  add(d, from, bytes, time);
  if (!can_wait) end_turn(d);
  return CallSpan{from, std::clamp(decided_to(d), from, end), handed_to};
}

void SegmentedBus::end_turn(Direction d) {
  impl_->session.end_turn(d);
}

std::uint64_t SegmentedBus::decided_to(Direction d) const {
  return impl_->streams[index_of(d)].decided_to;
}

std::span<const BusPiece> SegmentedBus::pieces(Direction d, std::uint64_t from,
                                               std::uint64_t to) const {
  const std::vector<BusPiece>& all = impl_->streams[index_of(d)].pieces;
  const auto by_offset = [](const BusPiece& p, std::uint64_t o) { return p.offset < o; };
  const auto first = std::lower_bound(all.begin(), all.end(), from, by_offset);
  const auto last = std::lower_bound(first, all.end(), to, by_offset);
  return {all.data() + (first - all.begin()), static_cast<std::size_t>(last - first)};
}

const BusSession& SegmentedBus::session() const {
  return impl_->session;
}

}  // namespace pvtap
