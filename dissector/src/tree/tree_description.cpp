#include "tree/tree_description.h"

#include <string>
#include <string_view>

#include "pvtap/codec/function_codes.h"
#include "pvtap/matching/reply_rules.h"
#include "tree/link_description.h"
#include "tree/modbus_description.h"
#include "tree/tree_builder.h"
#include "tree/value_description.h"

namespace pvtap::dissector {
namespace {

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
    return b.finish(kDefaultDialect);
  } catch (...) {
    return {};
  }
}

}  // namespace pvtap::dissector
