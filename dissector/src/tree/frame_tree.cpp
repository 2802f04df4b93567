#include "tree/frame_tree.h"

#include <epan/expert.h>
#include <epan/proto.h>

#include "fields/register_fields.h"
#include "pvtap/codec/function_codes.h"
#include "pvtap/registers/register_format.h"

namespace pvtap::dissector {
namespace {

// Warnings that point at a probable error in the data rather than a gap in the map.
constexpr auto kSuspicious =
    static_cast<guint16>(static_cast<unsigned>(ValueWarning::LowPartOver9999) |
                         static_cast<unsigned>(ValueWarning::InvalidBcd) |
                         static_cast<unsigned>(ValueWarning::InvalidDate));

// Builder: one frame's subtree under construction.
struct Builder {
  const TreeTarget& t;
  proto_tree* tree;

  const CommonFields& hf() const { return t.protocol->hf; }
  ExpertFields& ei() const { return t.protocol->ei; }
  gint at(FieldSpan s) const { return t.offset + s.offset; }

  // Fields a protocol does not register (-1) are skipped rather than asserted on.
  proto_item* uint(int id, FieldSpan s, guint32 value) const {
    if (id < 0 || !s.present()) return nullptr;
    return proto_tree_add_uint(tree, id, t.tvb, at(s), s.length, value);
  }
  proto_item* generated_uint(int id, guint32 value) const {
    if (id < 0) return nullptr;
    proto_item* item = proto_tree_add_uint(tree, id, t.tvb, t.offset, 0, value);
    proto_item_set_generated(item);
    return item;
  }
};

void add_device(const Builder& b, const FramePlan& plan) {
  const FrameLayout& l = plan.layout;
  if (!l.device_type.present()) return;
  const FieldSpan whole{l.device_type.offset,
                        static_cast<std::uint16_t>(l.device_type.length + l.device_serial.length)};
  proto_item* item = proto_tree_add_uint_format_value(
      b.tree, b.hf().device, b.t.tvb, b.at(whole), whole.length, plan.device_raw, "%s",
      plan.device_text != nullptr ? plan.device_text : "");
  const Builder sub{b.t, proto_item_add_subtree(item, b.t.protocol->ett.device)};
  sub.uint(b.hf().device_type, l.device_type, plan.device_type);
  sub.uint(b.hf().device_serial, l.device_serial, plan.device_serial);
}

void add_start(const Builder& b, const FramePlan& plan) {
  const FieldSpan s = plan.layout.start;
  if (!s.present()) return;
  proto_tree_add_uint_format_value(b.tree, b.hf().start, b.t.tvb, b.at(s), s.length, plan.start,
                                   "%s", plan.start_text);
}

// Header fields in wire order: a counted reply's byte count and device number come before
// the register it echoes; a GSL 0x10 request's byte count comes after its count.
void add_header(const Builder& b, const FramePlan& plan) {
  const CommonFields& hf = b.hf();
  const FrameLayout& l = plan.layout;
  b.uint(hf.station, l.station, plan.station);
  b.uint(hf.function, l.function, plan.function);
  const bool counted_reply = l.byte_count.present() && l.byte_count.offset == 2;
  if (counted_reply) {
    b.uint(hf.byte_count, l.byte_count, plan.byte_count);
    add_device(b, plan);
  }
  add_start(b, plan);
  b.uint(hf.count, l.count, plan.count);
  if (!counted_reply) b.uint(hf.byte_count, l.byte_count, plan.byte_count);
}

void add_exception(const Builder& b, const FramePlan& plan) {
  const FieldSpan s = plan.layout.exception_code;
  if (!s.present()) return;
  proto_item* item = b.uint(b.hf().exception_code, s, plan.exception_code);
  const std::string_view text = fc::exception_name(plan.exception_code);
  expert_add_info_format(b.t.pinfo, item, &b.ei().exception, "Exception reply: %.*s (code %u)",
                         static_cast<int>(text.size()), text.data(), plan.exception_code);
}

void add_value_warnings(const Builder& b, proto_item* item, const PlannedValue& v) {
  for (unsigned bit = 0; bit < 16; ++bit) {
    const auto w = static_cast<guint16>(1u << bit);
    if ((v.warnings & w) == 0) continue;
    const std::string_view why = describe(static_cast<ValueWarning>(w));
    expert_field* ei = (w & kSuspicious) != 0 ? &b.ei().value_suspicious : &b.ei().value_note;
    expert_add_info_format(b.t.pinfo, item, ei, "%s: %.*s", v.label, static_cast<int>(why.size()),
                           why.data());
  }
}

void add_flags(const Builder& b, proto_item* item, const PlannedValue& v, const RegisterField& f) {
  proto_tree* flags = proto_item_add_subtree(item, f.ett);
  for (int id : f.bits) {
    if (id >= 0) proto_tree_add_boolean(flags, id, b.t.tvb, b.at(v.span), v.span.length, v.raw);
  }
}

proto_item* add_value(const Builder& b, const PlannedValue& v, Dialect d) {
  const gint start = b.at(v.span);
  const gint length = v.span.length;
  const RegisterField* field = register_field(d, v.def);
  if (field == nullptr) {
    return proto_tree_add_uint_format(b.tree, b.hf().word, b.t.tvb, start, length, v.raw,
                                      "%s: %s (not in the register map)", v.label, v.text);
  }
  const int id = field->hf;
  switch (field->type) {
    case FT_DOUBLE:
      return proto_tree_add_double_format(b.tree, id, b.t.tvb, start, length, v.number, "%s: %s",
                                          v.label, v.text);
    case FT_STRING:
      return proto_tree_add_string_format(b.tree, id, b.t.tvb, start, length, v.text, "%s: %s",
                                          v.label, v.text);
    default:
      break;
  }
  proto_item* item = proto_tree_add_uint_format(b.tree, id, b.t.tvb, start, length, v.raw, "%s: %s",
                                                v.label, v.text);
  if (field->ett >= 0) add_flags(b, item, v, *field);
  return item;
}

void add_values(const Builder& b, const FramePlan& plan) {
  for (std::size_t i = 0; i < plan.value_count; ++i) {
    const PlannedValue& v = plan.values[i];
    add_value_warnings(b, add_value(b, v, plan.dialect), v);
  }
  if (plan.decode_note == nullptr) return;
  expert_field* ei = plan.start_assumed ? &b.ei().start_assumed : &b.ei().start_unknown;
  proto_tree_add_expert_format(b.tree, b.t.pinfo, ei, b.t.tvb, b.at(plan.layout.words),
                               plan.layout.words.length, "%s", plan.decode_note);
}

void add_check(const Builder& b, const FramePlan& plan) {
  const FieldSpan s = plan.layout.check;
  if (!s.present()) return;
  const CommonFields& hf = b.hf();
  proto_item* item = b.uint(hf.check, s, plan.check.found);
  if (!plan.check_verified) {
    b.generated_uint(hf.check_status, PROTO_CHECKSUM_E_UNVERIFIED);
    return;
  }
  b.generated_uint(hf.check_status, plan.check.ok ? PROTO_CHECKSUM_E_GOOD : PROTO_CHECKSUM_E_BAD);
  if (plan.check.ok) return;
  b.generated_uint(hf.check_expected, plan.check.expected);
  expert_add_info_format(b.t.pinfo, item, &b.ei().bad_check, "Bad %s 0x%04X, expected 0x%04X",
                         b.t.protocol->check_word, plan.check.found, plan.check.expected);
}

const char* unanswered_reason(const FrameRecord& r) {
  if (!r.timed_out) return "no reply before the end of the capture";
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
      return "no reply within the reply timeout";
    case TimeoutReason::NextRequestFirst:
      return "the master sent its next request to the station first";
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

void add_request_links(const Builder& b, const FrameRecord& r) {
  if (shown(r.response)) {
    b.generated_uint(b.hf().response_in, r.response->packet);
    return;
  }
  // Only a later pass knows that no reply came.
  if (!PINFO_FD_VISITED(b.t.pinfo) || !r.matched) return;
  proto_item* item =
      proto_tree_add_expert_format(b.tree, b.t.pinfo, &b.ei().unanswered, b.t.tvb, b.t.offset, 0,
                                   "Request never answered: %s", unanswered_reason(r));
  if (shown(r.next_request)) proto_item_append_text(item, " (frame %u)", r.next_request->packet);
}

void add_reply_links(const Builder& b, const FrameRecord& r) {
  if (shown(r.request)) {
    b.generated_uint(b.hf().request_in, r.request->packet);
    // The latency the bus session measured (as pvtap audit reports it); a duplicate has none.
    nstime_t delta;
    if (r.has_latency) {
      nstime_set_zero(&delta);
      const double ns = r.latency * 1e9;
      delta.secs = static_cast<time_t>(r.latency);
      delta.nsecs = static_cast<int>(ns - static_cast<double>(delta.secs) * 1e9);
    } else {
      const nstime_t shown{static_cast<time_t>(r.time.secs), r.time.nsecs};
      const nstime_t asked{static_cast<time_t>(r.request->time.secs), r.request->time.nsecs};
      nstime_delta(&delta, &shown, &asked);
    }
    proto_item* item =
        proto_tree_add_time(b.tree, b.hf().response_time, b.t.tvb, b.t.offset, 0, &delta);
    proto_item_set_generated(item);
  }
  if (r.duplicate) {
    proto_tree_add_expert_format(b.tree, b.t.pinfo, &b.ei().duplicate, b.t.tvb, b.t.offset, 0,
                                 "Duplicate reply: the station answered its request again");
  }
  if (r.unsolicited) {
    proto_tree_add_expert(b.tree, b.t.pinfo, &b.ei().unsolicited, b.t.tvb, b.t.offset, 0);
  }
  if (shown(r.late_for)) {
    proto_tree_add_expert_format(b.tree, b.t.pinfo, &b.ei().late_reply, b.t.tvb, b.t.offset, 0,
                                 "Reply after its request in frame %u timed out",
                                 r.late_for->packet);
  }
}

void add_count_mismatch(const Builder& b, const FrameRecord& r) {
  if (!r.count_mismatch) return;
  const char* unit = r.count_unit == CountUnit::Words ? "words" : "bytes";
  proto_item* item = b.generated_uint(b.hf().expected_count, r.count_expected);
  expert_add_info_format(b.t.pinfo, item, &b.ei().count_mismatch,
                         "The request asked for %u %s, the reply carries %u", r.count_expected,
                         unit, r.count_found);
}

void add_matching(const Builder& b, const FrameRecord& r) {
  if (r.role_corrected) {
    proto_tree_add_expert(b.tree, b.t.pinfo, &b.ei().role_corrected, b.t.tvb, b.t.offset, 0);
  }
  if (r.role == Role::Request) {
    add_request_links(b, r);
  } else {
    add_reply_links(b, r);
    add_count_mismatch(b, r);
  }
}

}  // namespace

void add_frame_tree(const TreeTarget& t, const FramePlan& plan, const FrameRecord& record) {
  proto_item* top =
      proto_tree_add_item(t.tree, t.protocol->proto, t.tvb, t.offset, t.length, ENC_NA);
  proto_item_append_text(top, ", %s", plan.summary);
  const Builder b{t, proto_item_add_subtree(top, t.protocol->ett.frame)};
  b.generated_uint(b.hf().dialect, static_cast<guint32>(plan.dialect));
  b.generated_uint(b.hf().role, static_cast<guint32>(plan.role));
  if (!plan.parsed) {
    expert_add_info_format(t.pinfo, top, &b.ei().malformed, "Malformed frame: %s",
                           plan.parse_error);
    b.uint(b.hf().station, plan.layout.station, plan.station);
    b.uint(b.hf().function, plan.layout.function, plan.function);
    add_check(b, plan);
    add_matching(b, record);
    return;
  }
  add_header(b, plan);
  add_exception(b, plan);
  add_values(b, plan);
  add_check(b, plan);
  add_matching(b, record);
}

void add_noise_tree(const TreeTarget& t, const std::optional<UnknownFunctionFrame>& unknown) {
  proto_item* top =
      proto_tree_add_item(t.tree, t.protocol->proto, t.tvb, t.offset, t.length, ENC_NA);
  proto_item_append_text(top, ", noise (%d bytes)", t.length);
  const Builder b{t, proto_item_add_subtree(top, t.protocol->ett.noise)};
  proto_item* bytes = proto_tree_add_item(b.tree, b.hf().noise, t.tvb, t.offset, t.length, ENC_NA);
  if (!unknown) {
    expert_add_info(t.pinfo, bytes, &b.ei().noise);
    return;
  }
  b.uint(b.hf().station, FieldSpan{0, 1}, unknown->station);
  proto_item* item = b.uint(b.hf().unknown_function, FieldSpan{1, 1}, unknown->function);
  expert_add_info_format(t.pinfo, item, &b.ei().unknown_function,
                         "Frame with a good CRC and the unknown function code 0x%02X",
                         unknown->function);
}

}  // namespace pvtap::dissector
