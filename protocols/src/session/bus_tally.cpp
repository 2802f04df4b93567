#include "session/bus_tally.h"

namespace pvtap::detail {
namespace {

template <typename T>
bool wants_example(const std::vector<T>& examples) {
  return examples.size() < BusReport::kMaxExamples;
}

}  // namespace

FrameExample BusTally::example_of(const SessionFrame& f) {
  FrameExample e;
  e.id = f.id;
  e.time = f.start_time;
  e.dialect = f.dialect;
  e.role = f.role;
  e.station = f.frame != nullptr ? f.frame->station : (f.bytes.empty() ? 0 : f.bytes[0]);
  e.function = f.frame != nullptr ? f.frame->function : 0;
  e.check = f.check;
  e.bytes.assign(f.bytes.begin(), f.bytes.end());
  return e;
}

void BusTally::count_exception(const SessionFrame& f) {
  const std::optional<std::uint8_t> code = exception_code(f);
  // A gateway's 0x0B is counted with the timeouts (gateway_timeouts), not as the device's.
  if (!code || gateway_timeout(f)) return;
  ++exception_codes_[{f.dialect, *code}];
}

void BusTally::add_frame(const SessionFrame& f) {
  // The request it repeats was counted; the echo is the tap's adapter's.
  if (f.echo) {
    ++counts_.echoes;
    return;
  }
  events_.add(f);
  stations_.add_frame(f);
  if (!f.check.ok && wants_example(bad_check_examples_)) {
    bad_check_examples_.push_back(example_of(f));
  }
  if (!f.parse_error.empty()) ++counts_.malformed_frames;
  if (f.frame == nullptr) return;
  const auto dialect = static_cast<std::size_t>(f.dialect);
  if (f.role == Role::Request) {
    ++counts_.requests;
    ++counts_.by_dialect[dialect].requests;
  } else {
    ++counts_.responses;
    ++counts_.by_dialect[dialect].responses;
  }
  if (f.unsolicited) {
    if (f.late_by) ++counts_.late_replies;
    if (wants_example(unsolicited_examples_)) {
      unsolicited_examples_.push_back(example_of(f));
    }
  }
  if (f.duplicate) ++counts_.duplicates;
  if (f.address_conflict) ++counts_.address_conflicts;
  if (f.count_mismatch) ++counts_.count_mismatches;
  if (f.role_corrected) ++counts_.role_corrections;
  if (f.dialect_changed_from) ++counts_.dialect_changes;
  if (f.quantity_problem) ++counts_.quantity_problems;
  if (f.broadcast_not_allowed) ++counts_.forbidden_broadcasts;
  if (f.write_count_problem) ++counts_.write_count_problems;
  count_exception(f);
}

void BusTally::add_transaction(const Transaction& t) {
  ++counts_.transactions;
  stations_.add_transaction(t);
  if (!t.reply_check_ok) ++counts_.damaged_replies;
}

void BusTally::add_timeout(const SessionTimeout& t) {
  events_.add(t);
  stations_.add_timeout(t);
  if (t.kind != UnansweredKind::Timeout) return;
  ++counts_.timeouts_by_reason[t.timeout.reason == TimeoutReason::NextRequestFirst ? 1 : 0];
  if (wants_example(timeout_examples_)) {
    timeout_examples_.push_back(TimeoutExample{t.timeout, t.request_start});
  }
}

void BusTally::add_gap(const SessionGap& g) {
  events_.add(g);
}

void BusTally::fill(BusReport& r) const {
  r.counters() = counts_;
  const EventCounts& e = events_.counts();
  r.timeouts = e.timeouts;
  r.unanswered_damaged_requests = e.unanswered_damaged_requests;
  r.unanswered_at_end = e.unanswered_at_end;
  r.unanswered_after_loss = e.unanswered_after_loss;
  r.unsolicited = e.unsolicited;
  r.exceptions = e.exceptions;
  r.gateway_timeouts = e.gateway_timeouts;
  r.gaps = e.gaps;
  r.line_errors = e.line_errors;
  r.exception_codes.clear();
  for (const auto& [key, count] : exception_codes_) {
    r.exception_codes.push_back(ExceptionTally{key.first, key.second, count});
  }
  r.bad_check_examples = bad_check_examples_;
  r.timeout_examples = timeout_examples_;
  r.unsolicited_examples = unsolicited_examples_;
}

}  // namespace pvtap::detail
