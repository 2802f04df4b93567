#include "pvtap/session/bus_session.h"

#include <algorithm>
#include <array>
#include <limits>
#include <vector>

#include "dialects/dialect_module.h"
#include "dialects/modbus/station_dialects.h"
#include "pvtap/codec/checksums.h"
#include "pvtap/codec/function_codes.h"
#include "pvtap/framing/framing_probe.h"
#include "pvtap/matching/reply_rules.h"
#include "pvtap/session/event_tally.h"
#include "pvtap/session/station_rule.h"
#include "pvtap/statistics/bus_timing.h"
#include "session/bus_session_impl.h"
#include "session/bus_tally.h"
#include "session/collision_tally.h"
#include "session/reply_values.h"
#include "session/session_times.h"

namespace pvtap {
namespace {

// What the matcher found about a frame, in the frame's event.
void take_findings(SessionFrame& out, Frame& frame, const FrameMatch& match, bool has_timestamps) {
  frame.role = match.role;
  out.role = match.role;
  out.role_corrected = match.role_correction.has_value();
  // A second reply that differs is another device's answer, not a repetition.
  out.address_conflict = match.duplicate && match.duplicate->other_content;
  out.duplicate = match.duplicate && !out.address_conflict;
  if (match.duplicate) out.duplicate_of = match.duplicate->original_request_id;
  if (out.address_conflict && has_timestamps) out.conflict_after = match.duplicate->since_request;
  out.count_mismatch = match.count_mismatch;
  if (match.unsolicited) {
    out.unsolicited = true;
    if (match.unsolicited->late_for_request_id) {
      out.late_by = match.unsolicited->since_request;
      out.late_for = match.unsolicited->late_for_request_id;
    }
  }
}

// A frame's content in brief (ObservedFrame::content): its check and length. A carried frame's
// check is the one computed for the codec, the last two bytes of `wire`.
std::uint32_t content_of(const FrameEvent& e, std::span<const std::uint8_t> wire) {
  std::uint32_t check = e.check.found;
  if (e.check.carried && wire.size() >= 2) {
    check = static_cast<std::uint32_t>(wire[wire.size() - 2]) |
            (static_cast<std::uint32_t>(wire.back()) << 8);
  }
  return (check << 16) | static_cast<std::uint32_t>(wire.size() & 0xFFFFu);
}

// The station a latency belongs to: the transaction's, since a damaged reply's may be wrong.
std::optional<std::uint8_t> answering_station(const FrameMatch& match) {
  if (!match.transaction) return std::nullopt;
  return transaction_station(*match.transaction);
}

}  // namespace

void BusSession::Impl::report(const Timeout& t) {
  SessionTimeout out;
  out.timeout = t;
  out.station = unanswered_station(t);
  const detail::RequestRecord* request = replies.waiting_request(t);
  if (request != nullptr) {
    out.request_start = request->start_time;
    out.request_end = request->end_time;
  }
  out.time = out.request_end + t.waited;
  if (t.reason == TimeoutReason::CaptureEnded) {
    out.kind = UnansweredKind::InputEnded;
  } else if (t.request_id < loss_boundary_id) {
    out.kind = UnansweredKind::AfterLoss;
  } else if (!t.request_check_ok) {
    out.kind = UnansweredKind::DamagedRequest;
  }
  tally.add_timeout(out);
  if (options.has_timestamps) collisions.add_timeout(out);
  sink.on_timeout(out);
}

void BusSession::Impl::on_frame(Direction direction, const FrameEvent& e,
                                std::span<const std::uint8_t> wire) {
  SessionFrame out;
  out.id = next_id++;
  out.offset = e.offset;
  out.bytes = e.bytes;
  out.direction = direction;
  out.start_time = options.has_timestamps ? e.start_time : 0.0;
  out.end_time = options.has_timestamps ? e.end_time : 0.0;
  times.settle_start(out);
  out.dialect = e.dialect;
  out.role = e.role;
  out.check = e.check;
  out.parse_error = parse_frame_into(wire, e.dialect, e.role, frame);
  const bool parsed = out.parse_error.empty();
  // A frame whose byte count lies (damaged, or sent so with a good check) does not parse, but
  // it was sent: its header is enough to pair it and count it.
  if (!parsed) {
    frame =
        e.check.ok ? sent_header(wire, e.dialect, e.role) : frame_header(wire, e.dialect, e.role);
  }
  const auto label = station_dialects.label(frame, e.check.ok);
  frame.dialect = label.dialect;
  out.dialect = label.dialect;
  out.dialect_changed_from = label.changed_from;
  const RegisterMap* own = decoder.station_map(frame.station);
  const RegisterMap*& of_dialect = dialect_maps[static_cast<std::size_t>(label.dialect)];
  if (own == nullptr && of_dialect == nullptr) of_dialect = &decoder.map(label.dialect);
  out.map = own != nullptr ? own : of_dialect;
  out.frame = &frame;
  handle_parsed(out, e, content_of(e, wire));
  if (out.role == Role::Request && e.check.ok) {
    request_dialects[frame.station] =
        static_cast<std::uint8_t>(static_cast<unsigned>(out.dialect) + 1);
  }
  tally.add_frame(out);
  note_for_collisions(out);
  sink.on_frame(out);
  name_collisions(false);
}

// Requests sent while another's reply was due show a second master as they come. Two poll
// cycles show it only over the whole input (a part of it can show cycles that are not there:
// a block skipped for a fault looks like another period), so they are looked at the end.
void BusSession::Impl::name_collisions(bool at_end) {
  if (!options.has_timestamps) return;
  if (!collisions.has_second_master() &&
      (times.requests_while_reply_due() >= kSecondMasterRequests ||
       (at_end && collisions.waiting() && times.report(timestamp_quality()).masters.size() >= 2))) {
    collisions.second_master();
  }
  collisions.take_named([this](const SessionCollision& c) { sink.on_collision(c); });
}

void BusSession::Impl::note_for_collisions(const SessionFrame& out) {
  if (!options.has_timestamps || out.echo) return;
  if (!out.check.ok) {
    collisions.add_damage(out.start_time, out.end_time);
  } else if (out.role == Role::Request) {
    collisions.add_request(out);
  } else {
    collisions.add_other_frame(out);
  }
}

void BusSession::Impl::handle_parsed(SessionFrame& out, const FrameEvent& e,
                                     std::uint32_t content) {
  const bool role_known = out.direction != Direction::Unknown;
  FrameSummary summary = summarize(frame);
  const FrameMatch match =
      matcher.on_frame(ObservedFrame{out.id, summary, out.start_time, out.end_time, e.check.ok,
                                     role_known, answers_pending, content});
  // Before the request is remembered: a request it gave up is looked up by its slot.
  report(match.timeouts);
  if (match.echo) {
    out.echo = true;
    out.echo_of = match.echo->request_id;
    out.station = frame.station;
    times.add(out, frame, std::nullopt, e.max_inner_gap);
    return;
  }
  if (match.transaction) tally.add_transaction(*match.transaction);
  take_findings(out, frame, match, options.has_timestamps);
  out.station = frame_station(e.check.ok, frame.station, match);
  if (match.role == Role::Request) {
    // Only the Modbus family limits quantities: the call is skipped for the rest.
    if (e.check.ok && modbus_family(frame.dialect)) {
      out.quantity_problem = pvtap::quantity_problem(frame);
      // Each rule is asked only of the frames it can concern: those to address 0, those with a
      // byte count.
      if (frame.station == fc::kModbusBroadcast) {
        out.broadcast_not_allowed = pvtap::broadcast_not_allowed(frame, true);
      }
      if (frame.byte_count) out.write_count_problem = pvtap::write_count_problem(frame);
    }
    replies.remember_request(out, frame);
    last_request_station = frame.station;
  } else {
    summary.role = match.role;
    out.reply_kind = reply_kind(summary);
  }
  replies.take(out, frame, match);
  times.add(out, frame, answering_station(match), e.max_inner_gap);
}

BusSession::BusSession(BusSessionOptions options, const RegisterDecoder& decoder,
                       BusSessionSink& sink)
    : impl_(std::make_unique<Impl>(options, decoder, sink)) {}

BusSession::~BusSession() = default;

void BusSession::turn_of(Direction direction, bool previous_turn_complete) {
  // Half duplex: when one side starts talking the other has finished its turn.
  const Direction previous = impl_->last_direction;
  impl_->last_direction = direction;
  if (direction != Direction::Unknown && previous != Direction::Unknown && previous != direction &&
      previous_turn_complete) {
    end_turn(previous);
  }
}

void BusSession::feed(const BusChunk& chunk) {
  turn_of(chunk.direction, chunk.previous_turn_complete);
  if (chunk.bytes.empty()) return;
  impl_->times.seen(chunk.time);
  Impl::DirectionStream& s = impl_->stream(chunk.direction);
  s.last_feed_time = chunk.time;
  s.reassembler.feed(chunk);
}

void BusSession::feed_decided(const DecidedPiece& piece) {
  turn_of(piece.direction, true);
  if (piece.bytes.empty()) return;
  impl_->times.seen(piece.end_time);
  Impl::DirectionStream& s = impl_->stream(piece.direction);
  s.last_feed_time = piece.end_time;
  s.reassembler.feed_decided(piece);
}

// The dialect whose length rules a frame's bytes fit exactly, `asked` (the dialect of the last
// request to its station) first: a report server ID reply fits Hybrid's 0x11 as well, and only
// its request tells (PROTOCOLS.md section 6, "Overlap with Hybrid V2.2"). Failing any reading,
// `fallback`.
Dialect BusSession::Impl::reply_dialect(std::span<const std::uint8_t> wire, Role role,
                                        std::optional<Dialect> asked, Dialect fallback) const {
  const RoleHint hint = role == Role::Request ? RoleHint::Request : RoleHint::Response;
  const CandidateList readings =
      frame_candidates(wire, hint, options.reassembler.dialects, Plausibility::Ignore);
  std::optional<Dialect> first;
  for (std::size_t i = 0; i < readings.size; ++i) {
    const FrameCandidate& c = readings.items[i];
    if (c.length != wire.size() || c.role != role || !detail::dialect_module(c.dialect).rtu_framed)
      continue;
    if (asked && same_dialect(c.dialect, *asked)) return c.dialect;
    if (!first) first = c.dialect;
  }
  return first.value_or(fallback);
}

void BusSession::carried_frame(Direction direction, std::uint64_t offset,
                               std::span<const std::uint8_t> frame, double time,
                               bool answers_request) {
  Impl& m = *impl_;
  m.times.seen(time);
  // The codec reads RTU frames: the CRC a serial line would carry is appended for it alone;
  // the frame's bytes, its check verdict and the byte counts are the wire's.
  m.carried_wire.assign(frame.begin(), frame.end());
  const std::uint16_t crc = Crc16Modbus::compute(frame);
  m.carried_wire.push_back(static_cast<std::uint8_t>(crc & 0xFFu));
  m.carried_wire.push_back(static_cast<std::uint8_t>(crc >> 8));
  FrameEvent e;
  e.offset = offset;
  e.bytes = frame;
  e.start_time = time;
  e.end_time = time;
  e.role = direction == Direction::FromSlave ? Role::Response : Role::Request;
  const std::uint8_t station = frame.empty() ? 0 : frame[0];
  std::optional<Dialect> asked;
  if (e.role == Role::Response) asked = m.asked_dialect(station);
  // Failing any reading, the Modbus family's, which names what is wrong with the frame.
  const DialectSet enabled = m.options.reassembler.dialects;
  e.dialect = m.reply_dialect(m.carried_wire, e.role, asked, enabled.carried_fallback());
  e.check = FrameCheck{true, 0, 0, true};
  ++m.carried.frames;
  m.carried.bytes_in += frame.size();
  m.carried.frame_bytes += frame.size();
  m.answers_pending = answers_request;
  m.on_frame(direction, e, m.carried_wire);
  m.answers_pending = false;
}

void BusSession::whole_frame(const BusChunk& chunk, bool answers_request) {
  impl_->answers_pending = answers_request;
  feed(chunk);
  end_turn(chunk.direction);
  impl_->answers_pending = false;
}

void BusSession::carrier_no_reply(double time, std::uint8_t code) {
  Impl& m = *impl_;
  if (!m.last_request_station) return;
  m.times.seen(time);
  m.report(m.matcher.carrier_no_reply(*m.last_request_station, time, code));
}

void BusSession::end_turn(Direction direction) {
  auto& s = impl_->streams[index_of(direction)];
  if (s && s->reassembler.pending_bytes() > 0) s->reassembler.discontinuity();
}

void BusSession::data_lost(Direction direction, double time,
                           std::optional<std::uint64_t> lost_bytes) {
  Impl& m = *impl_;
  // Timeouts that fell due before the loss are plain timeouts.
  if (m.options.has_timestamps) m.report(m.matcher.advance(time));
  m.stream(direction).reassembler.discontinuity();
  m.loss_boundary_id = m.next_id;
  const SessionGap gap{direction, m.options.has_timestamps ? time : 0.0, lost_bytes};
  m.tally.add_gap(gap);
  m.sink.on_gap(gap);
}

void BusSession::line_error(const SessionLineError& e) {
  impl_->tally.add_line_error(e);
  impl_->sink.on_line_error(e);
}

void BusSession::driver_glitch(const SessionDriverGlitch& g) {
  impl_->tally.add_driver_glitch(g);
  impl_->sink.on_driver_glitch(g);
}

void BusSession::restart(Direction direction) {
  auto& s = impl_->streams[index_of(direction)];
  if (s) s->reassembler.discontinuity();
  impl_->last_direction = Direction::Unknown;
}

void BusSession::idle(double now) {
  for (auto& s : impl_->streams) {
    if (s) s->reassembler.idle(now);
  }
  if (impl_->options.has_timestamps) impl_->report(impl_->matcher.advance(now));
}

std::optional<double> BusSession::next_deadline() const {
  const Impl& m = *impl_;
  std::optional<double> earliest;
  const auto consider = [&earliest](std::optional<double> t) {
    if (t && (!earliest || *t < *earliest)) earliest = t;
  };
  for (const auto& s : m.streams) {
    if (s) consider(s->reassembler.next_deadline());
  }
  if (m.options.has_timestamps) consider(m.matcher.next_deadline());
  return earliest;
}

void BusSession::finish() {
  Impl& m = *impl_;
  // The direction that spoke first ends first, so frames reach the matcher in bus order.
  std::vector<Impl::DirectionStream*> order;
  for (auto& s : m.streams) {
    if (s) order.push_back(s.get());
  }
  std::sort(order.begin(), order.end(),
            [](const auto* a, const auto* b) { return a->last_feed_time < b->last_feed_time; });
  for (auto* s : order) s->reassembler.finish();
  if (m.options.has_timestamps && m.times.any()) m.report(m.matcher.advance(m.times.last()));
  m.report(m.matcher.finish());
  m.name_collisions(true);
}

}  // namespace pvtap
