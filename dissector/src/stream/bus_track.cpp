#include "stream/bus_track.h"

#include <epan/wmem_scopes.h>

#include <memory>
#include <new>

#include "settings/register_decoding.h"

namespace pvtap::dissector {
namespace {

std::vector<std::unique_ptr<BusTrack>> g_tracks;

guint16 clamp16(unsigned value) {
  return static_cast<guint16>(value > 0xFFFF ? 0xFFFF : value);
}

}  // namespace

FrameRecord* new_frame_record() {
  return new (wmem_alloc(wmem_file_scope(), sizeof(FrameRecord))) FrameRecord{};
}

BusSessionOptions bus_session_options(const ProtocolSettings& s, Timestamping timestamping) {
  BusSessionOptions o;
  o.reassembler.dialects = DialectSet::all();  // a gateway may carry ASCII and RTU stations
  o.reassembler.baud = s.baud >= 300 ? s.baud : 9600;
  // What the timestamps prove, as pvtap audit reads the same carrier.
  apply_timestamping(TimestampFacts{timestamping, s.gateway_gap_ms / 1000.0, {}}, o);
  if (s.reply_timeout_ms > 0) o.matcher.timeout = s.reply_timeout_ms / 1000.0;
  o.decode_values = false;  // decoded when shown, into the tree
  return o;
}

BusTrack::BusTrack(const ProtocolSettings& settings, Timestamping timestamping)
    : bus_(bus_session_options(settings, timestamping), register_decoder(), *this) {}

std::uint64_t BusTrack::stream_offset(Direction d, guint32 seq) {
  const std::size_t i = index_of(d);
  if (!seq_known_[i]) {
    first_seq_[i] = seq;
    seq_known_[i] = true;
  }
  return static_cast<guint32>(seq - first_seq_[i]);
}

std::uint64_t BusTrack::next_datagram(Direction d, std::size_t length) {
  const std::uint64_t start = datagram_end_[index_of(d)];
  datagram_end_[index_of(d)] = start + length;
  return start;
}

void link_frame_record(FrameRecord& r, const SessionFrame& f, std::span<FrameRecord* const> by_id) {
  const auto record = [by_id](std::uint64_t id) { return id < by_id.size() ? by_id[id] : nullptr; };
  if (f.request_id) {
    r.request = record(*f.request_id);
    if (r.request != nullptr && r.request->response == nullptr) r.request->response = &r;
  }
  if (f.duplicate_of) r.request = record(*f.duplicate_of);
  if (f.late_for) r.late_for = record(*f.late_for);
  if (f.placed_by) r.placed_by = record(*f.placed_by);
  if (f.echo_of) r.echo_of = record(*f.echo_of);
}

void BusTrack::link(FrameRecord& r, const SessionFrame& f) const {
  link_frame_record(r, f, records_);
}

// What the session found of the frame's station: a quantity out of range, a change of
// dialect, and the name the station gave itself so far.
void BusTrack::note_findings(FrameRecord& r, const SessionFrame& f) {
  r.broadcast_not_allowed = f.broadcast_not_allowed;
  if (f.write_count_problem) {
    r.write_count_problem = true;
    r.write_count_expected = clamp16(f.write_count_problem->expected);
  }
  if (f.quantity_problem) {
    r.quantity_problem = true;
    r.quantity_write_part = f.quantity_problem->write_part;
    r.quantity_found = clamp16(f.quantity_problem->found);
    r.quantity_min = clamp16(f.quantity_problem->min);
    r.quantity_max = clamp16(f.quantity_problem->max);
  }
  if (f.dialect_changed_from) {
    r.dialect_changed = true;
    r.previous_dialect = *f.dialect_changed_from;
  }
  r.station_name = names_.note(f);
}

void fill_frame_record(FrameRecord& rec, const SessionFrame& f) {
  FrameRecord* r = &rec;
  r->dialect = f.dialect;
  r->role = f.role;
  r->station = f.frame != nullptr ? f.frame->station : 0;
  r->function = f.frame != nullptr ? f.frame->function : 0;
  r->matched = f.frame != nullptr;
  r->check_ok = f.check.ok;
  r->carried = f.check.carried;
  r->role_corrected = f.role_corrected;
  r->unsolicited = f.unsolicited;
  r->duplicate = f.duplicate;
  r->address_conflict = f.address_conflict;
  r->echo = f.echo;
  r->values_trusted = f.values_trusted;
  if (f.latency) {
    r->has_latency = true;
    r->latency = *f.latency;
  }
  if (f.count_mismatch) {
    r->count_mismatch = true;
    r->count_unit = f.count_mismatch->unit;
    r->count_expected = clamp16(f.count_mismatch->expected);
    r->count_found = clamp16(f.count_mismatch->found);
  }
  if (r->role == Role::Request) {
    r->bytes =
        static_cast<const guint8*>(wmem_memdup(wmem_file_scope(), f.bytes.data(), f.bytes.size()));
    r->length = static_cast<guint16>(f.bytes.size());
  }
}

void BusTrack::on_frame(const SessionFrame& f) {
  FrameRecord* r = new_frame_record();
  fill_frame_record(*r, f);
  link(*r, f);
  note_findings(*r, f);
  if (records_.size() <= f.id) records_.resize(f.id + 1, nullptr);
  records_[f.id] = r;
}

void BusTrack::on_timeout(const SessionTimeout& t) {
  FrameRecord* r = record(t.timeout.request_id);
  if (r == nullptr) return;
  r->timed_out = true;
  r->timeout_reason = t.timeout.reason;
  r->unanswered = t.kind;
  if (t.timeout.next_request_id) r->next_request = record(*t.timeout.next_request_id);
  timeouts_.add(r);
}

BusTrack* new_bus_track(const ProtocolSettings& settings, Timestamping timestamping) {
  g_tracks.push_back(std::make_unique<BusTrack>(settings, timestamping));
  return g_tracks.back().get();
}

// A new capture file's stations are not the last one's: what their traffic taught (SunSpec
// chains) is forgotten with the tracks.
void release_bus_tracks() {
  g_tracks.clear();
  register_decoder().forget_learned();
}

}  // namespace pvtap::dissector
