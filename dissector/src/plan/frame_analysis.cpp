#include "plan/frame_analysis.h"

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "plan/modbus_analysis.h"
#include "pvtap/codec/checksums.h"
#include "pvtap/codec/function_codes.h"
#include "pvtap/matching/frame_summary.h"
#include "pvtap/registers/register_format.h"

namespace pvtap::dissector {
namespace {

// Warnings that the tree already shows in another way.
constexpr auto kShownElsewhere = static_cast<std::uint16_t>(ValueWarning::NotInMap);

std::string hex4(unsigned value) {
  static constexpr char kDigits[] = "0123456789ABCDEF";
  std::string out = "0x";
  for (int shift = 12; shift >= 0; shift -= 4) out += kDigits[(value >> shift) & 0xFu];
  return out;
}

// The start address as the reference writes it; GSL wire addresses map back to decimal IDs.
std::string start_text(Dialect d, std::uint16_t wire, GslIdReading ids) {
  const auto written = written_address_of(d, wire, ids);
  if (!written) return hex4(wire);
  const std::string text(format_register_address(d, *written).view());
  return decimal_register_ids(d) ? hex4(wire) + " (ID " + text + ")" : text;
}

void plan_header(const Frame& f, std::size_t length, const AnalysisContext& ctx, FramePlan& plan) {
  plan.parsed = true;
  plan.station = f.station;
  plan.function = f.function;
  plan.layout = frame_layout(f, length);
  correct_modbus_layout(f, plan.layout);
  if (f.start) {
    plan.start = *f.start;
    const GslIdReading ids = ctx.decoder->options().gsl_ids;
    plan.start_text = ctx.arena.copy(start_text(f.dialect, *f.start, ids));
  }
  if (f.count) plan.count = *f.count;
  if (f.byte_count) plan.byte_count = *f.byte_count;
  if (f.exception_code) plan.exception_code = *f.exception_code;
}

void plan_device(const Frame& f, const AnalysisContext& ctx, FramePlan& plan) {
  if (!f.device) return;
  const DecodedValue v = ctx.decoder->decode_device_number(*f.device);
  plan.device_type = f.device->type_code;
  plan.device_serial = f.device->serial;
  plan.device_raw = (std::uint32_t{f.device->type_code} << 24) | (f.device->serial & 0xFFFFFFu);
  plan.device_text = ctx.arena.copy(format_value(v));
}

// What the codec reads: a carried frame (Modbus/TCP: station and PDU) gets the CRC a serial
// line would carry appended, for parsing alone; its check is said to be not present.
std::span<const std::uint8_t> codec_bytes(std::span<const std::uint8_t> bytes, bool carried,
                                          const Arena& arena) {
  if (!carried) return bytes;
  auto* wire = arena.make_array<std::uint8_t>(bytes.size() + 2);
  std::copy(bytes.begin(), bytes.end(), wire);
  const std::uint16_t crc = Crc16Modbus::compute(bytes);
  wire[bytes.size()] = static_cast<std::uint8_t>(crc & 0xFFu);
  wire[bytes.size() + 1] = static_cast<std::uint8_t>(crc >> 8);
  return {wire, bytes.size() + 2};
}

// The request whose start places the reply's words, as the bus session chose it.
std::optional<Frame> placing_request(const FrameRecord& r, const Arena& arena) {
  const FrameRecord* q = r.placed_by;
  if (r.role != Role::Response || q == nullptr || q->bytes == nullptr) return std::nullopt;
  ParseOutcome parsed =
      parse_frame(codec_bytes({q->bytes, q->length}, q->carried, arena), q->dialect, Role::Request);
  if (!parsed) return std::nullopt;
  return std::move(parsed).value();
}

std::string value_label(const DecodedValue& v, Dialect d) {
  const std::string address(format_value_address(v, d).view());
  if (v.def == nullptr) return "word at " + address;
  return std::string(v.name()) + " (" + address + ")";
}

// The generic fields of a station map's entry, which Wireshark registered no field for.
void plan_map_entry(const DecodedValue& v, const std::string& text, const Arena& arena,
                    PlannedValue& p) {
  p.map_key = arena.copy(v.key());
  p.map_value = arena.copy(std::string(v.name()) + ": " + text);
}

PlannedValue plan_value(const DecodedValue& v, const DecodeReport& report, Dialect d, bool own_map,
                        const FramePlan& plan, const Arena& arena) {
  const auto index = static_cast<std::uint16_t>(v.wire_address - report.start) / address_step(d);
  PlannedValue p;
  p.def = v.def;
  p.span = plan.layout.word_span(index, v.words_present > 0 ? v.words_present : 1u);
  // As the text shows it: a display filter `== 220.6` finds it, and tshark 4.6, which
  // writes doubles in full, prints what the text says.
  p.number = value_as_shown(v);
  p.raw = v.raw;
  const std::string text = format_value(v);
  p.text = arena.copy(text);
  p.label = arena.copy(value_label(v, d));
  if (own_map && v.def != nullptr) plan_map_entry(v, text, arena, p);
  p.warnings = static_cast<std::uint16_t>(v.warnings & ~kShownElsewhere);
  return p;
}

void plan_values(const Frame& f, const Frame* request, const AnalysisContext& ctx,
                 FramePlan& plan) {
  std::vector<DecodedValue> values;
  const DecodeReport report = ctx.decoder->decode(f, request, values);
  plan.decode_status = report.status;
  plan.start_assumed = report.start_assumed;
  if (report.status == DecodeStatus::StartUnknown || report.start_assumed) {
    plan.decode_note = ctx.arena.copy(describe(report));
  }
  if (report.count == 0) return;
  // The decoder's rule: a station's own map decodes its GSL and plain Modbus frames, and its
  // values are addressed in the map's dialect.
  const RegisterMap* own = ctx.decoder->station_map(f.station);
  const bool own_map = own != nullptr && modbus_family(f.dialect);
  const Dialect d = own_map ? own->dialect() : f.dialect;
  auto* planned = ctx.arena.make_array<PlannedValue>(report.count);
  for (std::size_t i = 0; i < report.count; ++i) {
    planned[i] = plan_value(values[report.first + i], report, d, own_map, plan, ctx.arena);
  }
  plan.values = planned;
  plan.value_count = report.count;
}

std::string summary_text(const FramePlan& plan, const char* check_word) {
  const bool exception = plan.layout.exception_code.present();
  const auto function =
      static_cast<std::uint8_t>(exception ? plan.function & ~fc::kExceptionFlag : plan.function);
  std::string text(fc::function_name(plan.dialect, function));
  text += ' ';
  text += exception ? std::string_view("exception") : to_string(plan.role);
  text += ", station " + std::to_string(plan.station);
  if (plan.station_name != nullptr) text += " (" + std::string(plan.station_name) + ")";
  if (exception) {
    text += ": ";
    text += fc::exception_name(plan.dialect, plan.exception_code);
  } else if (plan.modbus.detail != nullptr) {
    text += ": ";
    text += plan.modbus.detail;
  }
  if (plan.check_verified && !plan.check.ok) {
    text += " [bad ";
    text += check_word;
    text += ']';
  }
  return text;
}

// A frame that does not parse still shows what every frame of its dialect has: the station
// and function the bus decided it by, and its check, which lies at its end.
void plan_unparsed_header(std::size_t length, const FrameRecord& r, FramePlan& plan) {
  plan.layout = header_layout(r.dialect, length);
  plan.station = r.station;
  plan.function = r.function;
}

void analyze(std::span<const std::uint8_t> bytes, const AnalysisContext& ctx, FramePlan& plan) {
  const FrameRecord& r = *ctx.record;
  plan.dialect = r.dialect;
  plan.station_name = r.station_name;
  plan.role = r.role;
  const std::span<const std::uint8_t> wire = codec_bytes(bytes, r.carried, ctx.arena);
  plan.check = r.carried ? FrameCheck{true, 0, 0, true} : verify_check(bytes, r.dialect);
  plan.check_verified = ctx.verify_check && !r.carried;
  ParseOutcome parsed = parse_frame(wire, r.dialect, r.role);
  if (!parsed) {
    plan_unparsed_header(wire.size(), r, plan);
    if (r.carried) plan.layout.check = FieldSpan{};
    plan.parse_error = ctx.arena.copy(parsed.diagnostics());
    plan.summary = ctx.arena.copy("malformed frame: " + parsed.error_text());
    return;
  }
  Frame& f = parsed.value();
  plan_header(f, wire.size(), ctx, plan);
  if (r.carried) plan.layout.check = FieldSpan{};
  // Values only from a good check, placed only by a request with one (as pvtap audit).
  const std::optional<Frame> request =
      r.values_trusted ? placing_request(r, ctx.arena) : std::optional<Frame>();
  if (ctx.with_values) {
    plan_device(f, ctx, plan);
    if (r.values_trusted) plan_values(f, request ? &*request : nullptr, ctx, plan);
  }
  // The Info column names coils and devices, so this runs without a tree too.
  if (r.values_trusted) {
    plan_modbus(f, request ? &*request : nullptr, ctx.with_values, ctx.arena, plan);
  }
  plan.summary = ctx.arena.copy(summary_text(plan, ctx.check_word));
}

}  // namespace

void analyze_frame(std::span<const std::uint8_t> bytes, const AnalysisContext& ctx,
                   FramePlan& plan) noexcept {
  try {
    analyze(bytes, ctx, plan);
  } catch (...) {
    // Only allocation can fail in here; show the frame as undecoded rather than crash.
    plan.parsed = false;
    plan.parse_error = "the frame could not be decoded (out of memory)";
    plan.summary = plan.parse_error;
  }
}

}  // namespace pvtap::dissector
