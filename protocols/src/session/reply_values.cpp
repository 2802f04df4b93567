#include "session/reply_values.h"

namespace pvtap::detail {

const RequestRecord* ReplyValues::answered_request(SessionFrame& out,
                                                   const FrameMatch& match) const {
  if (match.transaction) {
    const Transaction& t = *match.transaction;
    out.request_id = t.request_id;
    out.broadcast_answer = t.broadcast;
    if (has_timestamps_) out.latency = t.latency;
    const std::size_t slot = t.broadcast ? RequestBook::kBroadcastSlot : t.station;
    return requests_.find(slot, t.request_id);
  }
  // A duplicate carries the words of the request it answered before.
  if (match.duplicate) {
    const DuplicateReply& d = *match.duplicate;
    return requests_.find(RequestBook::slot_of(d.dialect, d.station), d.original_request_id);
  }
  // A late reply carries the words of the request it came too late for: it is labelled late,
  // not also without a request.
  if (match.unsolicited && match.unsolicited->late_for_request_id) {
    const UnsolicitedReply& u = *match.unsolicited;
    return requests_.find(RequestBook::slot_of(u.dialect, u.station), *u.late_for_request_id);
  }
  return nullptr;
}

void ReplyValues::take(SessionFrame& out, const Frame& frame, const FrameMatch& match) {
  const RequestRecord* request = answered_request(out, match);
  // A request with a bad check may carry a corrupted start address: do not place words by it.
  const bool sound = request != nullptr && request->check_ok;
  if (sound) out.placed_by = request->id;
  const Frame* sound_request = sound ? &request->frame : nullptr;
  out.placing_request = sound_request;
  out.values_trusted = out.check.ok;
  if (!out.values_trusted) return;
  if (out.role == Role::Response && out.reply_kind == ReplyKind::Normal) {
    latest_.store(frame, sound_request, out.start_time);
  }
  if (decode_values_) decode(out, frame, sound_request);
}

void ReplyValues::decode(SessionFrame& out, const Frame& frame, const Frame* request) {
  values_.clear();
  // The device number heads every reply that carries one (Hybrid's), so it comes first.
  if (frame.role == Role::Response && frame.device) {
    values_.push_back(decoder_.decode_device_number(*frame.device));
  }
  out.decode = decoder_.decode(frame, request, values_);
  out.values = values_;
}

}  // namespace pvtap::detail
