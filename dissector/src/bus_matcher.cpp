#include "bus_matcher.h"

#include <memory>

namespace pvtap::dissector {
namespace {

std::vector<std::unique_ptr<BusMatcher>> g_matchers;

guint16 clamp16(unsigned value) {
  return static_cast<guint16>(value > 0xFFFF ? 0xFFFF : value);
}

}  // namespace

BusMatcher::BusMatcher(MatcherConfig config) : matcher_(*this, config) {}

void BusMatcher::observe(FrameRecord& record, const FrameSummary& summary, bool role_known) {
  if (records_.empty()) origin_ = record.time;
  nstime_t since{};
  nstime_delta(&since, &record.time, &origin_);
  const double t = nstime_to_sec(&since);
  ObservedFrame frame;
  frame.id = records_.size();
  frame.frame = summary;
  frame.start_time = t;
  frame.end_time = t;
  frame.check_ok = record.check_ok;
  frame.role_known = role_known;
  records_.push_back(&record);
  record.matched = true;
  record.role = matcher_.on_frame(frame);
}

FrameRecord* BusMatcher::at(std::uint64_t id) const {
  return id < records_.size() ? records_[id] : nullptr;
}

void BusMatcher::on_transaction(const Transaction& t) {
  FrameRecord* request = at(t.request_id);
  FrameRecord* response = at(t.response_id);
  if (request == nullptr || response == nullptr) return;
  response->request = request;
  if (request->response == nullptr) request->response = response;
}

void BusMatcher::on_timeout(const Timeout& t) {
  FrameRecord* request = at(t.request_id);
  if (request == nullptr) return;
  request->timed_out = true;
  request->timeout_reason = t.reason;
  if (t.next_request_id) request->next_request = at(*t.next_request_id);
}

void BusMatcher::on_unsolicited(const UnsolicitedReply& u) {
  FrameRecord* reply = at(u.response_id);
  if (reply == nullptr) return;
  reply->unsolicited = true;
  if (u.late_for_request_id) reply->late_for = at(*u.late_for_request_id);
}

void BusMatcher::on_duplicate(const DuplicateReply& d) {
  FrameRecord* reply = at(d.response_id);
  if (reply == nullptr) return;
  reply->duplicate = true;
  reply->request = at(d.original_request_id);
}

void BusMatcher::on_byte_count_mismatch(const ByteCountMismatch& m) {
  FrameRecord* reply = at(m.response_id);
  if (reply == nullptr) return;
  reply->count_mismatch = true;
  reply->count_unit = m.unit;
  reply->count_expected = clamp16(m.expected);
  reply->count_found = clamp16(m.found);
}

void BusMatcher::on_role_corrected(const RoleCorrection& c) {
  FrameRecord* frame = at(c.frame_id);
  if (frame == nullptr) return;
  frame->role = c.corrected;
  frame->role_corrected = true;
}

BusMatcher* new_bus_matcher(double reply_timeout_seconds) {
  MatcherConfig config;
  if (reply_timeout_seconds > 0) config.timeout = reply_timeout_seconds;
  g_matchers.push_back(std::make_unique<BusMatcher>(config));
  return g_matchers.back().get();
}

void release_bus_matchers() {
  g_matchers.clear();
}

}  // namespace pvtap::dissector
