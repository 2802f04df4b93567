#include "tree/tree_description.h"

#include <algorithm>
#include <cstdarg>
#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

#include "fields/register_field_type.h"
#include "pvtap/codec/function_codes.h"
#include "pvtap/matching/reply_rules.h"
#include "pvtap/registers/register_format.h"
#include "tree/modbus_description.h"
#include "tree/tree_builder.h"

namespace pvtap::dissector {
namespace {

// Warnings that point at a probable error in the data rather than a gap in the map.
constexpr auto kSuspicious =
    static_cast<std::uint16_t>(static_cast<unsigned>(ValueWarning::LowPartOver9999) |
                               static_cast<unsigned>(ValueWarning::InvalidBcd) |
                               static_cast<unsigned>(ValueWarning::InvalidDate));

// printf-style text, for the sentences that print numbers in hex.
[[gnu::format(printf, 1, 2)]] std::string printed(const char* format, ...) {
  char text[160];
  va_list args;
  va_start(args, format);
  const int n = std::vsnprintf(text, sizeof text, format, args);
  va_end(args);
  return std::string(text,
                     static_cast<std::size_t>(std::clamp(n, 0, static_cast<int>(sizeof text) - 1)));
}

std::uint32_t add_top(Builder& b, Subtree subtree, std::string_view appended) {
  TreeItem top;
  top.field = TreeField::Protocol;
  top.type = ValueType::Bytes;
  top.depth = kTop;
  top.length = b.ctx().length;
  top.appended = b.text(appended);
  top.subtree = subtree;
  return b.add(top);
}

void add_device(Builder& b, const FramePlan& plan) {
  const FrameLayout& l = plan.layout;
  if (!l.device_type.present()) return;
  TreeItem device;
  device.field = TreeField::Device;
  device.depth = kFrame;
  device.offset = l.device_type.offset;
  device.length = l.device_type.length + l.device_serial.length;
  device.uint = plan.device_raw;
  device.form = LabelForm::Value;
  device.text = plan.device_text != nullptr ? plan.device_text : "";
  device.subtree = Subtree::Device;
  b.add(device);
  b.uint(TreeField::DeviceType, l.device_type, plan.device_type, kField);
  b.uint(TreeField::DeviceSerial, l.device_serial, plan.device_serial, kField);
}

void add_start(Builder& b, const FramePlan& plan) {
  const FieldSpan s = plan.layout.start;
  if (!s.present()) return;
  TreeItem& start = b.item(*b.uint(TreeField::Start, s, plan.start));
  start.form = LabelForm::Value;
  start.text = plan.start_text;
}

// The core's reply rule decides what a Hybrid error reply is, as it does for pvtap audit.
bool hybrid_error_reply(const FramePlan& plan) {
  FrameSummary reply;
  reply.dialect = plan.dialect;
  reply.function = plan.function;
  return plan.parsed && plan.role == Role::Response && reply_kind(reply) == ReplyKind::HybridError;
}

// A Hybrid error reply carries 0x1000 0x00FF where other replies echo a start and a count:
// shown as the fixed body it is, and raised as the exception reply it is (pvtap audit counts
// it with the exceptions).
void add_error_body(Builder& b, const FramePlan& plan) {
  const FieldSpan start = plan.layout.start;
  const FieldSpan count = plan.layout.count;
  if (!start.present() || !count.present()) return;
  const FieldSpan body{start.offset,
                       static_cast<std::uint16_t>(count.offset + count.length - start.offset)};
  const std::uint32_t value = (std::uint32_t{plan.start} << 16) | plan.count;
  const auto item = b.uint(TreeField::ErrorBody, body, value);
  b.expert_on(item, TreeExpert::Exception,
              printed("Error reply: the inverter rejected the request (body 0x%04X 0x%04X)",
                      static_cast<unsigned>(plan.start), static_cast<unsigned>(plan.count)));
}

// The function field names codes by the dialect that first has them (0x11 0x17 0x18 are
// Hybrid's); a plain Modbus frame names its own.
void add_function(Builder& b, const FramePlan& plan) {
  const auto item = b.uint(TreeField::Function, plan.layout.function, plan.function);
  if (!item || plan.dialect != Dialect::Modbus) return;
  const bool exception = fc::is_gsl_exception(plan.function);
  const auto base =
      static_cast<std::uint8_t>(exception ? plan.function & ~fc::kExceptionFlag : plan.function);
  std::string name(fc::function_name(plan.dialect, base));
  if (exception) name = "exception (" + name + ")";
  TreeItem& function = b.item(*item);
  function.form = LabelForm::Value;
  function.text = b.text(name + printed(" (0x%02x)", static_cast<unsigned>(plan.function)));
}

// Header fields in wire order: a counted reply's byte count and device number come before
// the register it echoes; a GSL 0x10 request's byte count comes after its count.
void add_header(Builder& b, const FramePlan& plan) {
  const FrameLayout& l = plan.layout;
  const auto station = b.uint(TreeField::Station, l.station, plan.station);
  if (station && plan.station_name != nullptr) {
    TreeItem& item = b.item(*station);
    item.form = LabelForm::Value;
    item.text = b.text(std::to_string(plan.station) + " (" + plan.station_name + ")");
  }
  add_station_name(b, plan);
  add_function(b, plan);
  const bool counted_reply = l.byte_count.present() && l.byte_count.offset == 2;
  if (counted_reply) {
    b.uint(TreeField::ByteCount, l.byte_count, plan.byte_count);
    add_device(b, plan);
  }
  if (hybrid_error_reply(plan)) {
    add_error_body(b, plan);
    return;
  }
  add_start(b, plan);
  b.uint(TreeField::Count, l.count, plan.count);
  if (!counted_reply) b.uint(TreeField::ByteCount, l.byte_count, plan.byte_count);
}

void add_exception(Builder& b, const FramePlan& plan) {
  const FieldSpan s = plan.layout.exception_code;
  if (!s.present()) return;
  const auto item = b.uint(TreeField::ExceptionCode, s, plan.exception_code);
  // The dialect's own reading of the code: GSL's seed and Modbus name codes 1-3 and 6 apart.
  const std::string_view name = fc::exception_name(plan.dialect, plan.exception_code);
  if (item) {
    TreeItem& code = b.item(*item);
    code.form = LabelForm::Value;
    code.text = b.text(std::string(name) + " (" + std::to_string(plan.exception_code) + ")");
  }
  b.expert_on(item, TreeExpert::Exception,
              "Exception reply: " + std::string(name) + " (code " +
                  std::to_string(plan.exception_code) + ")");
}

void add_value_warnings(Builder& b, std::uint32_t item, const PlannedValue& v) {
  for (unsigned bit = 0; bit < 16; ++bit) {
    const auto w = static_cast<std::uint16_t>(1u << bit);
    if ((v.warnings & w) == 0) continue;
    const std::string_view why = describe(static_cast<ValueWarning>(w));
    const TreeExpert expert =
        (w & kSuspicious) != 0 ? TreeExpert::ValueSuspicious : TreeExpert::ValueNote;
    b.expert_on(item, expert, std::string(text_of(v.label)) + ": " + std::string(why));
  }
}

// The named flags of a bits register, one item each in bit order.
void add_flags(Builder& b, const PlannedValue& v) {
  unsigned named = 0;
  for (const BitName& named_bit : v.def->bits) {
    if (named_bit.index < 16 && !named_bit.name.empty()) named |= 1u << named_bit.index;
  }
  for (std::uint8_t bit = 0; bit < 16; ++bit) {
    if ((named & (1u << bit)) == 0) continue;
    TreeItem flag;
    flag.field = TreeField::RegisterFlag;
    flag.type = ValueType::Boolean;
    flag.depth = kField;
    flag.offset = v.span.offset;
    flag.length = v.span.length;
    flag.uint = v.raw;
    flag.def = v.def;
    flag.bit = bit;
    b.add(flag);
  }
}

bool numeric(const RegisterDef& def) {
  return def.kind != RegisterKind::Text && def.kind != RegisterKind::BcdYearMonth;
}

// A value of a station's own map, which has no field of its own (Wireshark registers fields
// at start-up; the table of station maps changes at run time): the generic map fields, with
// the entry's key and, for numbers, the number under it.
std::uint32_t add_map_value(Builder& b, const PlannedValue& v) {
  TreeItem item;
  item.field = TreeField::Modbus;
  item.modbus = ModbusField::MapValue;
  item.type = ValueType::String;
  item.form = LabelForm::Whole;
  item.depth = kFrame;
  item.offset = v.span.offset;
  item.length = v.span.length;
  item.string = v.map_value;
  item.text = b.text(std::string(text_of(v.label)) + ": " + std::string(text_of(v.text)));
  item.subtree = Subtree::MapEntry;
  const std::uint32_t index = b.add(item);
  TreeItem key = item;
  key.modbus = ModbusField::MapKey;
  key.form = LabelForm::Default;
  key.depth = kField;
  key.string = v.map_key;
  key.text = nullptr;
  key.subtree = Subtree::None;
  key.generated = true;
  b.add(key);
  if (!numeric(*v.def)) return index;
  TreeItem number = key;
  number.modbus = ModbusField::MapNumber;
  number.type = ValueType::Double;
  number.generated = false;
  // Integer kinds (raw words, enumerations, bits) as their integer, the rest as shown.
  number.number = register_field_type(*v.def) == RegisterFieldType::Double
                      ? v.number
                      : static_cast<double>(v.raw);
  b.add(number);
  return index;
}

std::uint32_t add_value(Builder& b, const PlannedValue& v) {
  if (v.map_key != nullptr && v.def != nullptr) return add_map_value(b, v);
  TreeItem item;
  item.depth = kFrame;
  item.offset = v.span.offset;
  item.length = v.span.length;
  item.form = LabelForm::Whole;
  item.uint = v.raw;
  if (v.def == nullptr) {
    item.field = TreeField::Word;
    item.text = b.text(std::string(text_of(v.label)) + ": " + std::string(text_of(v.text)) +
                       " (not in the register map)");
    return b.add(item);
  }
  item.field = TreeField::RegisterValue;
  item.def = v.def;
  item.text = b.text(std::string(text_of(v.label)) + ": " + std::string(text_of(v.text)));
  switch (register_field_type(*v.def)) {
    case RegisterFieldType::Double:
      item.type = ValueType::Double;
      item.number = v.number;
      break;
    case RegisterFieldType::String:
      item.type = ValueType::String;
      item.string = v.text;
      break;
    case RegisterFieldType::Uint16:
    case RegisterFieldType::Uint32:
      item.subtree = v.def->kind == RegisterKind::Bits ? Subtree::Flags : Subtree::None;
      break;
  }
  const std::uint32_t index = b.add(item);
  if (item.subtree == Subtree::Flags) add_flags(b, v);
  return index;
}

void add_values(Builder& b, const FramePlan& plan) {
  for (std::size_t i = 0; i < plan.value_count; ++i) {
    const PlannedValue& v = plan.values[i];
    add_value_warnings(b, add_value(b, v), v);
  }
  if (plan.decode_note == nullptr) return;
  const TreeExpert expert =
      plan.start_assumed ? TreeExpert::StartAssumed : TreeExpert::StartUnknown;
  b.expert_item(expert, plan.layout.words, plan.decode_note);
}

void add_check(Builder& b, const FramePlan& plan) {
  if (plan.check.carried) {
    b.generated_uint(TreeField::CheckStatus, static_cast<std::uint32_t>(CheckStatus::NotPresent));
    return;
  }
  const FieldSpan s = plan.layout.check;
  if (!s.present()) return;
  const auto item = b.uint(TreeField::Check, s, plan.check.found);
  const auto status = [&](CheckStatus st) {
    b.generated_uint(TreeField::CheckStatus, static_cast<std::uint32_t>(st));
  };
  if (!plan.check_verified) {
    status(CheckStatus::Unverified);
    return;
  }
  status(plan.check.ok ? CheckStatus::Good : CheckStatus::Bad);
  if (plan.check.ok) return;
  b.generated_uint(TreeField::CheckExpected, plan.check.expected);
  b.expert_on(
      item, TreeExpert::BadCheck,
      printed("Bad %s 0x%04X, expected 0x%04X", b.ctx().check_word,
              static_cast<unsigned>(plan.check.found), static_cast<unsigned>(plan.check.expected)));
}

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

// The reason, and the request that came first where that was the reason.
std::string unanswered_text(const FrameRecord& r, const DescriptionContext& ctx) {
  std::string text = unanswered_reason(r, ctx);
  if (shown(r.next_request)) text += printed(" (frame %u)", r.next_request->packet);
  return text;
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

// The bytes a frame carries but the tree does not decode, as bytes: a reader sees what came,
// and that it was not trusted.
void add_undecoded(Builder& b, FieldSpan s, const char* why) {
  if (!s.present()) return;
  TreeItem item;
  item.field = TreeField::Undecoded;
  item.type = ValueType::Bytes;
  item.depth = kFrame;
  item.offset = s.offset;
  item.length = s.length;
  item.appended = b.text(printed(" (%u bytes, not decoded: %s)", s.length, why));
  b.add(item);
}

// The bytes between a frame's header (station and function) and its check.
FieldSpan body_span(const FrameLayout& l) {
  const int from = l.function.offset + l.function.length;
  if (!l.function.present() || !l.check.present() || l.check.offset <= from) return FieldSpan{};
  return FieldSpan{static_cast<std::uint16_t>(from),
                   static_cast<std::uint16_t>(l.check.offset - from)};
}

void describe(Builder& b, const FramePlan& plan, const FrameRecord& record) {
  const std::uint32_t top = add_top(b, Subtree::Frame, ", " + std::string(text_of(plan.summary)));
  b.generated_uint(TreeField::Dialect, static_cast<std::uint32_t>(plan.dialect));
  b.generated_uint(TreeField::Role, static_cast<std::uint32_t>(plan.role));
  if (!plan.parsed) {
    b.expert_on(top, TreeExpert::Malformed,
                "Malformed frame: " + std::string(text_of(plan.parse_error)));
    b.uint(TreeField::Station, plan.layout.station, plan.station);
    b.uint(TreeField::Function, plan.layout.function, plan.function);
    add_undecoded(b, body_span(plan.layout), "the frame did not parse");
    add_check(b, plan);
    add_matching(b, record);
    return;
  }
  add_header(b, plan);
  add_exception(b, plan);
  add_modbus_fields(b, plan);
  add_values(b, plan);
  if (!record.values_trusted && !record.check_ok) {
    add_undecoded(b, plan.layout.words, b.text(printed("the %s failed", b.ctx().check_word)));
  }
  add_check(b, plan);
  add_matching(b, record);
  add_station_findings(b, plan, record);
}

void describe_announcement(Builder& b, const FrameRecord& r) {
  add_top(b, Subtree::Frame, printed(", no reply to the request in frame %u", r.packet));
  // The station, for filters by station; no function or role, which would count it as a frame.
  b.generated_uint(TreeField::Station, r.station);
  const std::uint32_t request = b.generated_uint(TreeField::UnansweredRequest, r.packet);
  b.expert_on(
      request, TreeExpert::Unanswered,
      printed("Request in frame %u never answered: ", r.packet) + unanswered_text(r, b.ctx()));
}

void describe(Builder& b, const std::optional<UnknownFunctionFrame>& unknown) {
  add_top(b, Subtree::Noise, printed(", noise (%d bytes)", b.ctx().length));
  TreeItem noise;
  noise.field = TreeField::Noise;
  noise.type = ValueType::Bytes;
  noise.depth = kFrame;
  noise.length = b.ctx().length;
  const std::uint32_t bytes = b.add(noise);
  if (!unknown) {
    TreeItem expert;
    expert.kind = ItemKind::Expert;
    expert.expert = TreeExpert::Noise;
    expert.target = static_cast<std::int32_t>(bytes);
    b.add(expert);
    return;
  }
  b.uint(TreeField::Station, FieldSpan{0, 1}, unknown->station);
  const auto item = b.uint(TreeField::UnknownFunction, FieldSpan{1, 1}, unknown->function);
  b.expert_on(item, TreeExpert::UnknownFunction,
              printed("Frame with a good CRC and the unknown function code 0x%02X",
                      static_cast<unsigned>(unknown->function)));
}

}  // namespace

TreeDescription describe_frame(const FramePlan& plan, const FrameRecord& record,
                               const DescriptionContext& ctx) noexcept {
  try {
    Builder b(ctx);
    describe(b, plan, record);
    return b.finish(plan.dialect);
  } catch (...) {
    return {};  // out of memory: no tree rather than a crash
  }
}

TreeDescription describe_timeout(const FrameRecord& request,
                                 const DescriptionContext& ctx) noexcept {
  try {
    Builder b(ctx);
    describe_announcement(b, request);
    return b.finish(request.dialect);
  } catch (...) {
    return {};
  }
}

TreeDescription describe_noise(const std::optional<UnknownFunctionFrame>& unknown,
                               const DescriptionContext& ctx) noexcept {
  try {
    Builder b(ctx);
    describe(b, unknown);
    return b.finish(Dialect::Gsl);
  } catch (...) {
    return {};
  }
}

}  // namespace pvtap::dissector
