#include "tree/link_description.h"

#include "pvtap/matching/reply_rules.h"

namespace pvtap::dissector {
namespace {

std::string unanswered_reason(const FrameRecord& r, const DescriptionContext& ctx) {
  switch (r.unanswered) {
    case UnansweredKind::DamagedRequest:
      return "the request has a bad check: the slave rightly ignored it";
    case UnansweredKind::AfterLoss:
      return "capture data was lost while it waited: the reply may be in the gap";
    case UnansweredKind::InputEnded:
      return "no reply before the end of the capture";
    case UnansweredKind::Timeout:
      break;
  }
  switch (r.timeout_reason) {
    case TimeoutReason::NoReply:
      // The timeout is a preference: say which one judged, so that a reader can tell a
      // silent station from a timeout set too short.
      if (ctx.reply_timeout_ms == 0) return "no reply within the reply timeout";
      return printed("no reply within the reply timeout (%u ms)",
                     static_cast<unsigned>(ctx.reply_timeout_ms));
    case TimeoutReason::NextRequestFirst:
      return "the master sent its next request to the station first";
    case TimeoutReason::CarrierNoReply:
      return "no reply on the bus: the logger stick answered code 05";
    case TimeoutReason::CaptureEnded:
      break;
  }
  return "no reply before the end of the capture";
}

// A frame the session decided but no packet has shown yet (its bytes wait for the next
// segment of its direction) has no packet to link to.
bool shown(const FrameRecord* r) {
  return r != nullptr && r->packet != 0;
}

void add_request_links(Builder& b, const FrameRecord& r) {
  if (shown(r.response)) {
    b.generated_uint(TreeField::ResponseIn, r.response->packet);
    return;
  }
  // Only a later pass knows where the timeout was announced; the verdict stays there.
  if (!b.ctx().visited || r.announced_in == 0) return;
  TreeItem& item = b.item(b.generated_uint(TreeField::TimeoutIn, r.announced_in));
  item.form = LabelForm::Whole;
  item.text = b.text(printed("No reply: %s; announced in frame %u",
                             unanswered_text(r, b.ctx()).c_str(), r.announced_in));
}

// As Wireshark's nstime_delta: b - a, both parts of one sign.
RelativeTime time_between(const PacketTime& b, const PacketTime& a) {
  RelativeTime d{b.secs - a.secs, b.nsecs - a.nsecs};
  constexpr std::int32_t kNsPerSec = 1000000000;
  if (b.secs < a.secs && d.nsecs > 0) {
    d.nsecs -= kNsPerSec;
    d.secs += 1;
  } else if (b.secs > a.secs && d.nsecs < 0) {
    d.nsecs += kNsPerSec;
    d.secs -= 1;
  }
  return d;
}

// The latency the bus session measured (as pvtap audit reports it); a duplicate has none,
// and shows the time since its request's packet.
RelativeTime response_time(const FrameRecord& r) {
  if (!r.has_latency) return time_between(r.time, r.request->time);
  RelativeTime t;
  const double ns = r.latency * 1e9;
  t.secs = static_cast<std::int64_t>(r.latency);
  t.nsecs = static_cast<std::int32_t>(ns - static_cast<double>(t.secs) * 1e9);
  return t;
}

void add_reply_links(Builder& b, const FrameRecord& r) {
  if (shown(r.request)) {
    b.generated_uint(TreeField::RequestIn, r.request->packet);
    TreeItem time;
    time.field = TreeField::ResponseTime;
    time.type = ValueType::Time;
    time.depth = kFrame;
    time.generated = true;
    time.time = response_time(r);
    b.add(time);
  }
  if (r.duplicate) {
    b.expert_item(TreeExpert::Duplicate, FieldSpan{},
                  "Duplicate reply: the station answered its request again");
  }
  if (r.address_conflict) {
    b.expert_item(TreeExpert::AddressConflict, FieldSpan{},
                  "Address conflict: a second reply to the request, with other contents: two "
                  "devices answer to this station");
  }
  if (r.unsolicited) b.expert_item(TreeExpert::Unsolicited, FieldSpan{}, nullptr);
  if (shown(r.late_for)) {
    b.expert_item(
        TreeExpert::LateReply, FieldSpan{},
        b.text(printed("Reply after its request in frame %u timed out", r.late_for->packet)));
  }
}

void add_count_mismatch(Builder& b, const FrameRecord& r) {
  if (!r.count_mismatch) return;
  const char* unit = r.count_unit == CountUnit::Words ? "words" : "bytes";
  const std::uint32_t item = b.generated_uint(TreeField::ExpectedCount, r.count_expected);
  b.expert_on(
      item, TreeExpert::CountMismatch,
      printed("The request asked for %u %s, the reply carries %u",
              static_cast<unsigned>(r.count_expected), unit, static_cast<unsigned>(r.count_found)));
}

}  // namespace

// The reason, and the request that came first where that was the reason.
std::string unanswered_text(const FrameRecord& r, const DescriptionContext& ctx) {
  std::string text = unanswered_reason(r, ctx);
  if (shown(r.next_request)) text += printed(" (frame %u)", r.next_request->packet);
  return text;
}

void add_matching(Builder& b, const FrameRecord& r) {
  // An echo is the request again, not one of its own: it links to the request and no further.
  if (r.echo) {
    if (shown(r.echo_of)) b.generated_uint(TreeField::RequestIn, r.echo_of->packet);
    b.expert_item(TreeExpert::Echo, FieldSpan{},
                  shown(r.echo_of) ? b.text(printed("Echo of the request in frame %u: the tap's "
                                                    "adapter repeating it, counted once",
                                                    r.echo_of->packet))
                                   : nullptr);
    return;
  }
  // Read as a request, it echoes the pending one: a note only where the function's normal
  // reply is no echo.
  if (r.role_corrected && !reply_is_echo(r.dialect, r.function)) {
    b.expert_item(TreeExpert::RoleCorrected, FieldSpan{}, nullptr);
  }
  if (r.role == Role::Request) {
    add_request_links(b, r);
  } else {
    add_reply_links(b, r);
    add_count_mismatch(b, r);
  }
}

}  // namespace pvtap::dissector
