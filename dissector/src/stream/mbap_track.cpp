#include "stream/mbap_track.h"

#include <memory>

#include "pvtap/carriers/mbap_reader.h"
#include "settings/register_decoding.h"
#include "stream/bus_track.h"

namespace pvtap::dissector {
namespace {

std::vector<std::unique_ptr<MbapTrack>> g_tracks;

// What a frame says of itself before the session decides it: all a held request shows in a
// first pass.
void describe_itself(FrameRecord& r, Direction d, std::span<const std::uint8_t> frame) {
  r.dialect = kCarriedDialect;
  r.role = d == Direction::FromSlave ? Role::Response : Role::Request;
  r.station = frame.empty() ? 0 : frame[0];
  r.function = frame.size() < 2 ? 0 : frame[1];
  r.carried = true;
}

}  // namespace

MbapTrack::MbapTrack(const ProtocolSettings& settings)
    : session_(bus_session_options(settings, Timestamping::GatewaySegments), register_decoder(),
               *this),
      flow_(session_, settings.reply_timeout_ms > 0 ? settings.reply_timeout_ms / 1000.0 : 1.0) {}

FrameRecord* MbapTrack::feed(Direction d, std::span<const std::uint8_t> adu, double time) {
  FrameRecord* r = new_frame_record();
  if (adu.size() > kMbapCarrierBytes) describe_itself(*r, d, adu.subspan(kMbapCarrierBytes));
  by_offset_[{d, flow_.position(d)}] = r;
  flow_.feed(d, adu, time);
  return r;
}

void MbapTrack::on_frame(const SessionFrame& f) {
  const auto it = by_offset_.find({f.direction, f.offset});
  if (it == by_offset_.end()) return;
  FrameRecord* r = it->second;
  by_offset_.erase(it);
  fill_frame_record(*r, f);
  if (by_id_.size() <= f.id) by_id_.resize(f.id + 1, nullptr);
  by_id_[f.id] = r;
  link_frame_record(*r, f, by_id_);
  r->station_name = names_.note(f);
}

void MbapTrack::on_timeout(const SessionTimeout& t) {
  FrameRecord* r = t.timeout.request_id < by_id_.size() ? by_id_[t.timeout.request_id] : nullptr;
  if (r == nullptr) return;
  r->timed_out = true;
  r->timeout_reason = t.timeout.reason;
  r->unanswered = t.kind;
  timeouts_.add(r);
}

MbapTrack* new_mbap_track(const ProtocolSettings& settings) {
  g_tracks.push_back(std::make_unique<MbapTrack>(settings));
  return g_tracks.back().get();
}

void release_mbap_tracks() {
  g_tracks.clear();
}

}  // namespace pvtap::dissector
