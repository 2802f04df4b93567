#include "carriers/solarman_v5_track.h"

#include <algorithm>
#include <memory>

#include "pvtap/codec/checksums.h"
#include "pvtap/framing/framing_probe.h"
#include "settings/register_decoding.h"

namespace pvtap::dissector {
namespace {

namespace v5 = solarman_v5;

std::vector<std::unique_ptr<SolarmanV5Track>> g_tracks;

// What RTU bytes say of themselves before the bus decides them (a request held for its
// response): the dialect their station spoke so far (`known`), else the first reading their
// length fits; the check verdict by the CRC.
void describe_itself(FrameRecord& r, Direction d, std::span<const std::uint8_t> rtu,
                     const std::array<std::uint8_t, 256>& known) {
  r.role = d == Direction::FromSlave ? Role::Response : Role::Request;
  r.station = rtu.empty() ? 0 : rtu[0];
  r.function = rtu.size() < 2 ? 0 : rtu[1];
  r.check_ok = rtu.size() >= 4 && Crc16Modbus::compute(rtu) == 0;
  r.dialect = kCarriedDialect;
  if (known[r.station] != 0) {
    r.dialect = static_cast<Dialect>(known[r.station] - 1);
    return;
  }
  const RoleHint hint = r.role == Role::Request ? RoleHint::Request : RoleHint::Response;
  const CandidateList readings =
      frame_candidates(rtu, hint, DialectSet::all(), Plausibility::Ignore);
  for (std::size_t i = 0; i < readings.size; ++i) {
    const FrameCandidate& c = readings.items[i];
    if (c.length == rtu.size() && c.role == r.role && rtu_framed(c.dialect)) {
      r.dialect = c.dialect;
      break;
    }
  }
}

}  // namespace

SolarmanV5Track::SolarmanV5Track(BusTrack& offsets, const ProtocolSettings& settings)
    : offsets_(offsets),
      session_(bus_session_options(settings, Timestamping::LoggerStickFrames), register_decoder(),
               *this),
      pairing_(bus_session_options(settings, Timestamping::LoggerStickFrames).matcher.timeout,
               *this) {}

SegmentedBus::CallSpan SolarmanV5Track::show(Direction d, std::uint64_t from,
                                             std::span<const std::uint8_t> bytes, double time,
                                             bool can_wait) {
  Side& s = sides_[index_of(d)];
  const std::uint64_t end = from + bytes.size();
  const std::uint64_t handed_to = std::clamp(s.fed_to, from, end);
  if (from > s.fed_to) {
    keep(d, s.reader.discontinuity(), time);
    // As pvtap audit's flow: the bus is told once it has one.
    if (bus_started_) session_.data_lost(d, time, from - s.fed_to);
    s.shift += from - s.fed_to;
    s.fed_to = from;
  }
  if (end > s.fed_to) {
    keep(d, s.reader.feed(bytes.subspan(s.fed_to - from)), time);
    s.fed_to = end;
  }
  if (!can_wait) keep(d, s.reader.discontinuity(), time);
  const std::uint64_t decided = s.fed_to - s.reader.pending();
  return SegmentedBus::CallSpan{from, std::clamp(decided, from, end), handed_to};
}

// Each piece is kept before the pairing sees its frame: a release may point at it at once.
void SolarmanV5Track::keep(Direction d, std::span<const v5::Event> events, double time) {
  Side& s = sides_[index_of(d)];
  for (const v5::Event& e : events) {
    V5Piece& piece = s.pieces.emplace_back();
    piece.offset = e.offset + s.shift;
    piece.length = static_cast<std::uint32_t>(e.bytes.size());
    piece.kind = e.kind;
    piece.broken = e.broken;
    piece.claimed_size = static_cast<std::uint32_t>(e.claimed_size);
    if (e.kind != v5::Event::Kind::Frame) continue;
    if (e.frame.rtu_length > 0) {
      V5Rtu& rtu = rtus_.emplace_back();
      rtu.own = new_frame_record();
      describe_itself(*rtu.own, d, e.frame.rtu(), station_dialects_);
      const auto stick = pairing_.stick_serial();
      rtu.other_serial =
          e.frame.kind == v5::FrameKind::Request && stick && *stick != e.frame.header.serial;
      piece.rtu = &rtu;
    }
    pairing_.frame(e.frame, time, piece.offset);
  }
}

V5Piece* SolarmanV5Track::piece_at(Direction d, std::uint64_t offset) {
  std::vector<V5Piece>& all = sides_[index_of(d)].pieces;
  const auto it = std::lower_bound(all.begin(), all.end(), offset,
                                   [](const V5Piece& p, std::uint64_t o) { return p.offset < o; });
  return it != all.end() && it->offset == offset ? &*it : nullptr;
}

void SolarmanV5Track::release(const v5::Release& r) {
  using Kind = v5::Release::Kind;
  const Direction d = r.kind == Kind::Request ? Direction::ToSlave : Direction::FromSlave;
  V5Piece* piece = piece_at(d, r.offset);
  if (r.kind == Kind::Request || r.kind == Kind::Reply) {
    Side& s = sides_[index_of(d)];
    feeding_ = piece != nullptr ? piece->rtu : nullptr;
    bus_started_ = true;
    feeding_from_ = s.rtu_fed;
    session_.whole_frame(BusChunk{r.rtu, r.time, d}, r.answers_request);
    s.rtu_fed += r.rtu.size();
    feeding_ = nullptr;
    return;
  }
  if (r.kind == Kind::NoReply) {
    bus_started_ = true;
    session_.carrier_no_reply(r.time, r.code);
  }
  if (r.kind == Kind::Refused) {
    const V5Piece* request = piece_at(Direction::ToSlave, r.request_offset);
    if (request != nullptr && request->rtu != nullptr) request->rtu->refused = true;
  }
  if (piece == nullptr) return;
  piece->code_meaning = r.kind;
  piece->addressed_serial = r.addressed_serial;
}

void SolarmanV5Track::on_frame(const SessionFrame& f) {
  if (feeding_ == nullptr) return;
  // The first frame of the RTU bytes fills the record they were shown with so far.
  const bool first = std::none_of(feeding_->pieces.begin(), feeding_->pieces.end(),
                                  [](const RtuPiece& p) { return p.record != nullptr; });
  FrameRecord* r = first ? feeding_->own : new_frame_record();
  fill_frame_record(*r, f);
  if (by_id_.size() <= f.id) by_id_.resize(f.id + 1, nullptr);
  by_id_[f.id] = r;
  link_frame_record(*r, f, by_id_);
  r->station_name = names_.note(f);
  if (f.frame != nullptr && f.check.ok) {
    station_dialects_[f.frame->station] =
        static_cast<std::uint8_t>(static_cast<unsigned>(f.dialect) + 1);
  }
  feeding_->pieces.push_back(RtuPiece{static_cast<std::uint32_t>(f.offset - feeding_from_),
                                      static_cast<std::uint32_t>(f.bytes.size()), r});
}

void SolarmanV5Track::on_noise(const SessionNoise& n) {
  if (feeding_ == nullptr) return;
  feeding_->pieces.push_back(RtuPiece{static_cast<std::uint32_t>(n.noise.offset - feeding_from_),
                                      static_cast<std::uint32_t>(n.noise.bytes.size()), nullptr});
}

void SolarmanV5Track::on_timeout(const SessionTimeout& t) {
  FrameRecord* r = t.timeout.request_id < by_id_.size() ? by_id_[t.timeout.request_id] : nullptr;
  if (r == nullptr) return;
  r->timed_out = true;
  r->timeout_reason = t.timeout.reason;
  r->unanswered = t.kind;
  if (t.timeout.next_request_id && *t.timeout.next_request_id < by_id_.size()) {
    r->next_request = by_id_[*t.timeout.next_request_id];
  }
  timeouts_.add(r);
}

std::span<const V5Piece> SolarmanV5Track::pieces(Direction d, std::uint64_t from,
                                                 std::uint64_t to) const {
  const std::vector<V5Piece>& all = sides_[index_of(d)].pieces;
  const auto by_offset = [](const V5Piece& p, std::uint64_t o) { return p.offset < o; };
  const auto first = std::lower_bound(all.begin(), all.end(), from, by_offset);
  const auto last = std::lower_bound(first, all.end(), to, by_offset);
  return {all.data() + (first - all.begin()), static_cast<std::size_t>(last - first)};
}

SolarmanV5Track* new_v5_track(BusTrack& offsets, const ProtocolSettings& settings) {
  g_tracks.push_back(std::make_unique<SolarmanV5Track>(offsets, settings));
  return g_tracks.back().get();
}

void release_v5_tracks() {
  g_tracks.clear();
}

}  // namespace pvtap::dissector
