// TimelineCollector: frames, timeouts, noise and gaps into lanes, buckets and marks.
#include "html/timeline_collector.h"

#include <algorithm>
#include <cmath>

#include "pvtap/registers/register_format.h"
#include "report/frame_findings.h"
#include "writers/values_writer.h"

namespace pvtap::analyzer {
namespace {

std::size_t latency_bin(double seconds) {
  const double ms = seconds * 1e3;
  if (ms <= 1.0) return 0;
  const auto bin = static_cast<std::size_t>(std::floor(10.0 * std::log10(ms)));
  return std::min(bin, Lane::kLatencyBins - 1);
}

Mark frame_mark(std::uint32_t lane, const SessionFrame& f, MarkKind kind) {
  Mark m;
  m.time = f.start_time;
  m.lane = lane;
  m.kind = kind;
  m.dialect = f.dialect;
  m.is_request = f.role == Role::Request;
  if (f.frame != nullptr) {
    m.has_function = true;
    m.function = f.frame->function;
    m.start = f.frame->start;
    m.count = f.frame->count;
    if (f.frame->exception_code) m.detail = *f.frame->exception_code;
  }
  return m;
}

}  // namespace

TimelineCollector::BusState& TimelineCollector::bus_of(const EventContext& c) {
  timeline_.has_timestamps = c.has_timestamps;
  if (last_bus_ != nullptr && c.bus.data() == last_bus_name_) return *last_bus_;
  last_bus_name_ = c.bus.data();
  const auto it = buses_.find(c.bus);
  if (it != buses_.end()) return *(last_bus_ = &it->second);
  BusState& bus = buses_[std::string(c.bus)];
  last_bus_ = &bus;
  bus.name = c.bus;
  bus.bus_lane = static_cast<std::uint32_t>(timeline_.lanes.size());
  timeline_.lanes.push_back(Lane{std::string(c.bus), std::nullopt, {}, {}, {}, {}});
  bus.load = static_cast<std::uint32_t>(timeline_.loads.size());
  timeline_.loads.push_back(BusLoad{std::string(c.bus), {}, {}, {}});
  return bus;
}

std::uint32_t TimelineCollector::station_lane(BusState& bus, std::uint8_t station) {
  const auto it = bus.station_lanes.find(station);
  if (it != bus.station_lanes.end()) return it->second;
  const auto lane = static_cast<std::uint32_t>(timeline_.lanes.size());
  timeline_.lanes.push_back(Lane{bus.name, station, {}, {}, {}, {}});
  bus.station_lanes[station] = lane;
  return lane;
}

// A damaged frame's station byte may be the damage: it joins its station's lane only when
// that station has shown up in a good frame, else the bus lane (a day of line noise would
// otherwise open a lane for every address). The same for damaged requests left unanswered.
std::uint32_t TimelineCollector::lane_of(BusState& bus, const SessionFrame& f) {
  if (f.frame == nullptr) return bus.bus_lane;
  return f.check.ok ? station_lane(bus, f.frame->station) : known_lane(bus, f.frame->station);
}

std::uint32_t TimelineCollector::known_lane(const BusState& bus, std::uint8_t station) const {
  const auto it = bus.station_lanes.find(station);
  return it != bus.station_lanes.end() ? it->second : bus.bus_lane;
}

std::size_t TimelineCollector::bucket_of(double time) {
  int doublings = 0;
  const std::size_t index = grid_.index_of(time, doublings);
  for (int i = 0; i < doublings; ++i) {
    for (Lane& lane : timeline_.lanes) {
      lane.requests.halve();
      lane.replies.halve();
      lane.latency.halve();
    }
    for (BusLoad& load : timeline_.loads) {
      load.to_slave.halve();
      load.from_slave.halve();
      load.unknown.halve();
    }
    for (ValueSeries& s : timeline_.values) s.points.halve();
  }
  return index;
}

void TimelineCollector::add_mark(Mark mark) {
  const auto kind = static_cast<std::size_t>(mark.kind);
  if (marks_kept_[kind] >= Timeline::kMaxMarksPerKind) {
    ++timeline_.marks_dropped[kind];
    return;
  }
  ++marks_kept_[kind];
  timeline_.marks.push_back(mark);
}

void TimelineCollector::frame(const EventContext& c, const SessionFrame& f) {
  BusState& bus = bus_of(c);
  const std::uint32_t lane = lane_of(bus, f);
  const std::size_t bucket = bucket_of(f.start_time);
  count_frame(bus, lane, bucket, f);
  mark_frame(lane, f);
  if (frame_feeds_values(f)) add_values(lane, bucket, f);
  if (f.role == Role::Request) {
    note_request(bus, f.start_time);
    if (f.frame != nullptr) {
      recent_requests_[f.id % recent_requests_.size()] = {f.id, &bus, f.frame->start,
                                                          f.frame->count};
    }
  }
}

void TimelineCollector::count_frame(BusState& bus, std::uint32_t lane, std::size_t bucket,
                                    const SessionFrame& f) {
  if (f.echo) return;  // the tap's adapter's copy of a request counted already
  Lane& l = timeline_.lanes[lane];
  BusLoad& load = timeline_.loads[bus.load];
  const auto bytes = static_cast<double>(f.bytes.size());
  if (f.role == Role::Request) {
    l.requests.add(bucket, 1);
    load.to_slave.add(bucket, bytes);
  } else {
    l.replies.add(bucket, 1);
    load.from_slave.add(bucket, bytes);
  }
  if (f.latency) {
    l.latency.add(bucket, *f.latency);
    ++l.latency_bins[latency_bin(*f.latency)];
  }
}

void TimelineCollector::mark_frame(std::uint32_t lane, const SessionFrame& f) {
  if (!f.check.ok) add_mark(frame_mark(lane, f, MarkKind::Damaged));
  // The core counts an exception for a good reply of either error form (BusTally).
  const bool exception = f.check.ok && f.role == Role::Response && f.frame != nullptr &&
                         (f.reply_kind == ReplyKind::HybridError ||
                          (f.reply_kind == ReplyKind::GslException && f.frame->exception_code));
  if (exception) add_mark(frame_mark(lane, f, MarkKind::Exception));
  if (f.unsolicited) add_mark(frame_mark(lane, f, MarkKind::Unsolicited));
  if (f.duplicate) add_mark(frame_mark(lane, f, MarkKind::Duplicate));
}

void TimelineCollector::add_values(std::uint32_t lane, std::size_t bucket, const SessionFrame& f) {
  // Words no map names are kept apart by their table (holding and input registers).
  const RegisterTable unmapped =
      f.frame != nullptr ? unmapped_table(f.dialect, f.frame->function) : RegisterTable::Registers;
  for (const DecodedValue& v : f.values) {
    if (reading_kind(v) != ReadingKind::Number) continue;
    const bool mapped = v.def != nullptr;
    const SeriesKey key = mapped ? SeriesKey{lane, v.def, v.instance, RegisterTable::Registers}
                                 : SeriesKey{lane, nullptr, v.address, unmapped};
    auto [it, added] =
        series_.try_emplace(key, static_cast<std::uint32_t>(timeline_.values.size()));
    if (added) {
      ValueSeries s;
      s.lane = lane;
      s.dialect = f.dialect;
      s.def = v.def;
      s.instance = v.instance;
      s.table = key.table;
      s.key = mapped ? v.def->key : unmapped_key(unmapped, v.address).view();
      s.address = format_value_address(v, f.dialect).view();
      s.min = s.max = v.value;
      timeline_.values.push_back(std::move(s));
    }
    ValueSeries& s = timeline_.values[it->second];
    // Enums, bits and raw words chart as their integer; numbers as the scaled value.
    const double reading = !mapped || v.def->kind == RegisterKind::Number ||
                                   v.def->kind == RegisterKind::Bcd ||
                                   v.def->kind == RegisterKind::BcdPhaseCapacity
                               ? v.value
                               : static_cast<double>(v.raw);
    s.points.add(bucket, reading);
    s.min = std::min(s.min, reading);
    s.max = std::max(s.max, reading);
  }
}

void TimelineCollector::note_request(BusState& bus, double time) {
  if (bus.last_request && time - *bus.last_request >= Timeline::kMinSilence &&
      timeline_.silences.size() < Timeline::kMaxSilences) {
    timeline_.silences.push_back(PollSilence{bus.name, *bus.last_request, time});
  }
  bus.last_request = std::max(time, bus.last_request.value_or(time));
}

void TimelineCollector::timeout(const EventContext& c, const SessionTimeout& t) {
  const MarkKind kind = t.kind == UnansweredKind::Timeout          ? MarkKind::Timeout
                        : t.kind == UnansweredKind::DamagedRequest ? MarkKind::UnansweredDamaged
                                                                   : MarkKind::Noise;
  if (kind == MarkKind::Noise) return;  // not a finding: the input ended or data was lost
  BusState& bus = bus_of(c);
  Mark m;
  m.time = t.request_start;
  m.lane = kind == MarkKind::Timeout ? station_lane(bus, t.timeout.station)
                                     : known_lane(bus, t.timeout.station);
  m.kind = kind;
  m.dialect = t.timeout.dialect;
  m.has_function = true;
  m.function = t.timeout.function;
  m.is_request = true;
  const RequestBlock& r = recent_requests_[t.timeout.request_id % recent_requests_.size()];
  if (r.id == t.timeout.request_id && r.bus == &bus) {
    m.start = r.start;
    m.count = r.count;
  }
  add_mark(m);
}

void TimelineCollector::noise(const EventContext& c, const SessionNoise& n) {
  BusState& bus = bus_of(c);
  const std::size_t bucket = bucket_of(n.noise.start_time);
  BusLoad& load = timeline_.loads[bus.load];
  const auto bytes = static_cast<double>(n.noise.bytes.size());
  if (n.direction == Direction::ToSlave) {
    load.to_slave.add(bucket, bytes);
  } else if (n.direction == Direction::FromSlave) {
    load.from_slave.add(bucket, bytes);
  } else {
    load.unknown.add(bucket, bytes);
  }
  Mark m;
  m.time = n.noise.start_time;
  m.lane = bus.bus_lane;
  m.kind = MarkKind::Noise;
  m.detail = n.noise.bytes.size();
  add_mark(m);
}

void TimelineCollector::gap(const EventContext& c, const SessionGap& g) {
  BusState& bus = bus_of(c);
  Mark m;
  m.time = g.time;
  m.lane = bus.bus_lane;
  m.kind = MarkKind::Gap;
  m.detail = g.lost_bytes.value_or(0);
  add_mark(m);
}

void TimelineCollector::collision(const EventContext& c, const SessionCollision& k) {
  Mark m;
  m.time = k.start_time;
  m.lane = bus_of(c).bus_lane;
  m.kind = MarkKind::Collision;
  add_mark(m);
}

Timeline TimelineCollector::finish() {
  timeline_.start = grid_.start();
  timeline_.bucket_width = grid_.width();
  std::stable_sort(timeline_.marks.begin(), timeline_.marks.end(),
                   [](const Mark& a, const Mark& b) { return a.time < b.time; });
  return std::move(timeline_);
}

}  // namespace pvtap::analyzer
