#include "pvtap/session/bus_session.h"

#include <algorithm>
#include <array>
#include <limits>
#include <vector>

#include "matching/request_book.h"
#include "pvtap/matching/reply_rules.h"
#include "pvtap/statistics/timing_statistics.h"
#include "session/bus_tally.h"
#include "session/latest_readings.h"

namespace pvtap {
struct BusSession::Impl {
  // DirectionStream: the reassembler of one direction and where its events go.
  struct DirectionStream : ReassemblerSink {
    DirectionStream(Impl& o, Direction d)
        : owner(o), direction(d), reassembler(o.options.reassembler, *this) {}
    void on_frame(const FrameEvent& e) override { owner.on_frame(direction, e); }
    void on_noise(const NoiseEvent& e) override {
      const SessionNoise noise{e, direction};
      owner.tally.add_noise(noise);
      owner.sink.on_noise(noise);
    }

    Impl& owner;
    Direction direction;
    StreamReassembler reassembler;
    double last_feed_time = -std::numeric_limits<double>::infinity();
  };

  Impl(BusSessionOptions o, const RegisterDecoder& d, BusSessionSink& s)
      : options(o),
        decoder(d),
        sink(s),
        matcher(o.matcher),
        timing(BusTiming(o.reassembler.baud, o.reassembler.bits_per_char)) {}

  DirectionStream& stream(Direction d) {
    auto& slot = streams[index_of(d)];
    if (!slot) slot = std::make_unique<DirectionStream>(*this, d);
    return *slot;
  }

  void on_frame(Direction direction, const FrameEvent& e);
  void handle_parsed(SessionFrame& out, const FrameEvent& e);
  void take_findings(SessionFrame& out, const FrameMatch& match);
  const detail::RequestRecord* answered_request(SessionFrame& out, const FrameMatch& match);
  void note_transaction(SessionFrame& out, const Frame& frame, const FrameMatch& match);
  void decode_values(SessionFrame& out, const Frame* request);
  void add_timing(const SessionFrame& out, const FrameMatch& match, double max_inner_gap);
  // The station a latency belongs to: the request's, since a damaged reply's may be wrong.
  std::uint8_t answering_station(const FrameMatch& match) const {
    return match.transaction ? match.transaction->station : frame.station;
  }
  // Timeouts come before the frame that made them due.
  void report(std::span<const Timeout> timeouts) {
    for (const Timeout& t : timeouts) report(t);
  }
  void report(const Timeout& t);
  TimestampQuality timestamp_quality() const;
  ReassemblerTotals totals() const;
  void time_seen(double t);

  BusSessionOptions options;
  const RegisterDecoder& decoder;
  BusSessionSink& sink;
  std::array<std::unique_ptr<DirectionStream>, kDirections> streams;
  TransactionMatcher matcher;
  TimingStatistics timing;
  detail::BusTally tally;
  detail::LatestReadings latest;
  detail::RequestBook requests;
  Frame frame;  // the frame being handled; SessionFrame::frame points here
  std::vector<DecodedValue> values;
  std::uint64_t next_id = 0;
  std::uint64_t loss_boundary_id = 0;  // requests before this id were waiting during a loss
  Direction last_direction = Direction::Unknown;  // of the last chunk fed
  bool any_time = false;
  double first_time = 0;
  double last_time = 0;
  double bus_free_at = -std::numeric_limits<double>::infinity();  // end of the last frame
};

void BusSession::Impl::time_seen(double t) {
  if (!options.has_timestamps) return;
  if (!any_time) {
    first_time = last_time = t;
    any_time = true;
  }
  first_time = std::min(first_time, t);
  last_time = std::max(last_time, t);
}

void BusSession::Impl::report(const Timeout& t) {
  SessionTimeout out;
  out.timeout = t;
  const detail::RequestRecord* request =
      requests.find(detail::RequestBook::slot_of(t.dialect, t.station), t.request_id);
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
  sink.on_timeout(out);
}

void BusSession::Impl::on_frame(Direction direction, const FrameEvent& e) {
  SessionFrame out;
  out.id = next_id++;
  out.offset = e.offset;
  out.bytes = e.bytes;
  out.direction = direction;
  out.start_time = options.has_timestamps ? e.start_time : 0.0;
  out.end_time = options.has_timestamps ? e.end_time : 0.0;
  // A frame's start is estimated back from its last byte at the configured baud rate; a pty
  // or a gateway that delivers faster would put a reply's start before its request's end.
  // The bus is half duplex: nothing starts before the frame before it ended.
  if (options.has_timestamps && out.end_time >= bus_free_at) {
    if (out.start_time < bus_free_at) out.start_time = bus_free_at;
    bus_free_at = out.end_time;
  }
  out.dialect = e.dialect;
  out.role = e.role;
  out.check = e.check;
  ParseOutcome parsed = parse_frame(e.bytes, e.dialect, e.role);
  if (!parsed) out.parse_error = parsed.diagnostics();
  // A damaged frame whose byte count lies does not parse, but it was sent: its header is
  // enough to pair it and count it.
  if (parsed || !e.check.ok) {
    frame = parsed ? parsed.value() : frame_header(e.bytes, e.dialect, e.role);
    out.frame = &frame;
    handle_parsed(out, e);
  }
  tally.add_frame(out);
  sink.on_frame(out);
}

void BusSession::Impl::handle_parsed(SessionFrame& out, const FrameEvent& e) {
  const bool role_known = out.direction != Direction::Unknown;
  FrameSummary summary = summarize(frame);
  const FrameMatch match = matcher.on_frame(
      ObservedFrame{out.id, summary, out.start_time, out.end_time, e.check.ok, role_known});
  // Before the request is remembered: a request it gave up is looked up by its slot.
  report(match.timeouts);
  if (match.transaction) tally.add_transaction(*match.transaction);
  take_findings(out, match);
  if (match.role == Role::Request) {
    requests.remember(out.id, frame, out.start_time, out.end_time, e.check.ok);
  } else {
    summary.role = match.role;
    out.reply_kind = reply_kind(summary);
  }
  note_transaction(out, frame, match);
  add_timing(out, match, e.max_inner_gap);
}

void BusSession::Impl::take_findings(SessionFrame& out, const FrameMatch& match) {
  frame.role = match.role;
  out.role = match.role;
  out.role_corrected = match.role_correction.has_value();
  out.duplicate = match.duplicate.has_value();
  if (match.duplicate) out.duplicate_of = match.duplicate->original_request_id;
  out.count_mismatch = match.count_mismatch;
  if (match.unsolicited) {
    out.unsolicited = true;
    if (match.unsolicited->late_for_request_id) {
      out.late_by = match.unsolicited->since_request;
      out.late_for = match.unsolicited->late_for_request_id;
    }
  }
}

const detail::RequestRecord* BusSession::Impl::answered_request(SessionFrame& out,
                                                                const FrameMatch& match) {
  if (match.transaction) {
    const Transaction& t = *match.transaction;
    out.request_id = t.request_id;
    out.broadcast_answer = t.broadcast;
    if (options.has_timestamps) out.latency = t.latency;
    const std::size_t slot = t.broadcast ? detail::RequestBook::kBroadcastSlot : t.station;
    return requests.find(slot, t.request_id);
  }
  // A duplicate carries the words of the request it answered before.
  if (match.duplicate) {
    const DuplicateReply& d = *match.duplicate;
    return requests.find(detail::RequestBook::slot_of(d.dialect, d.station), d.original_request_id);
  }
  return nullptr;
}

void BusSession::Impl::note_transaction(SessionFrame& out, const Frame& reply,
                                        const FrameMatch& match) {
  const detail::RequestRecord* request = answered_request(out, match);
  // A request with a bad check may carry a corrupted start address: do not place words by it.
  const bool sound = request != nullptr && request->check_ok;
  if (sound) out.placed_by = request->id;
  const Frame* sound_request = sound ? &request->frame : nullptr;
  out.values_trusted = out.check.ok;
  if (!out.values_trusted) return;
  if (out.role == Role::Response && out.reply_kind == ReplyKind::Normal) {
    latest.store(reply, sound_request, out.start_time);
  }
  if (options.decode_values) decode_values(out, sound_request);
}

void BusSession::Impl::decode_values(SessionFrame& out, const Frame* request) {
  values.clear();
  // The device number heads every Hybrid reply, so it comes first.
  if (frame.dialect == Dialect::Hybrid && frame.role == Role::Response && frame.device) {
    values.push_back(decoder.decode_device_number(*frame.device));
  }
  out.decode = decoder.decode(frame, request, values);
  out.values = values;
}

void BusSession::Impl::add_timing(const SessionFrame& out, const FrameMatch& match,
                                  double max_inner_gap) {
  if (!options.has_timestamps) return;
  // With timestamps declared too coarse the bus gaps are never judged; requests alone give
  // the poll periods, and the gap statistics are spared the other frames.
  if (options.reassembler.timestamps == TimestampTrust::Untrusted && out.role != Role::Request) {
    if (out.latency) timing.add_latency(answering_station(match), *out.latency);
    return;
  }
  timing.add_frame(FrameTiming{out.id, frame.dialect, out.role, frame.station, frame.function,
                               out.start_time, out.end_time, max_inner_gap, frame.start,
                               frame.count, out.check.ok});
  if (out.latency) timing.add_latency(answering_station(match), *out.latency);
}

BusSession::BusSession(BusSessionOptions options, const RegisterDecoder& decoder,
                       BusSessionSink& sink)
    : impl_(std::make_unique<Impl>(options, decoder, sink)) {}

BusSession::~BusSession() = default;

void BusSession::feed(const BusChunk& chunk) {
  // Half duplex: when one side starts talking the other has finished its turn.
  const Direction previous = impl_->last_direction;
  impl_->last_direction = chunk.direction;
  if (chunk.direction != Direction::Unknown && previous != Direction::Unknown &&
      previous != chunk.direction && chunk.previous_turn_complete) {
    end_turn(previous);
  }
  if (chunk.bytes.empty()) return;
  impl_->time_seen(chunk.time);
  Impl::DirectionStream& s = impl_->stream(chunk.direction);
  s.last_feed_time = chunk.time;
  s.reassembler.feed(chunk);
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
  if (m.options.has_timestamps && m.any_time) m.report(m.matcher.advance(m.last_time));
  m.report(m.matcher.finish());
}

ReassemblerTotals BusSession::Impl::totals() const {
  ReassemblerTotals sum;
  for (const auto& s : streams) {
    if (s) sum += s->reassembler.totals();
  }
  return sum;
}

TimestampQuality BusSession::Impl::timestamp_quality() const {
  if (!options.has_timestamps) return {false, "the input has no timestamps (a plain byte dump)"};
  for (const auto& s : streams) {
    if (!s || s->reassembler.timing_trusted()) continue;
    const bool declared = options.reassembler.timestamps == TimestampTrust::Untrusted;
    if (declared && !options.timestamp_note.empty()) {
      return {false, std::string(options.timestamp_note)};
    }
    return {false, std::string(s->reassembler.timing_reason())};
  }
  return {true, ""};
}

const EventTally& BusSession::tally() const {
  return impl_->tally.events();
}

ReassemblerTotals BusSession::totals() const {
  return impl_->totals();
}

BusReport BusSession::report() const {
  const Impl& m = *impl_;
  BusReport r;
  m.tally.fill(r);
  r.bytes = m.totals();
  r.has_timestamps = m.options.has_timestamps;
  r.first_time = m.first_time;
  r.last_time = m.last_time;
  r.timing = m.timing.report(m.timestamp_quality());
  m.tally.fill_stations(r);
  const auto readings = m.latest.decode(m.decoder);
  for (StationSummary& s : r.stations) {
    for (const StationLatency& l : r.timing.latency_by_station) {
      if (l.station == s.station) s.latency = l.latency;
    }
    const auto it = readings.find(s.station);
    if (it == readings.end()) continue;
    s.last_report_time = it->second.last_time;
    s.latest_values = it->second.values;
  }
  return r;
}

}  // namespace pvtap
