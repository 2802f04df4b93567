#include "report/frame_findings.h"

#include <algorithm>
#include <array>
#include <iterator>

#include "formatting/number_text.h"
#include "pvtap/codec/function_codes.h"
#include "pvtap/matching/reply_rules.h"
#include "pvtap/registers/register_format.h"

namespace pvtap::analyzer {
namespace {

void add_count_mismatch(const ByteCountMismatch& m, std::vector<std::string>& out) {
  std::string text = m.unit == CountUnit::Words ? "word count " : "byte count ";
  append_uint(text, m.found);
  text += ", the request asks for ";
  append_uint(text, m.expected);
  out.push_back(std::move(text));
}

void add_quantity_problem(const QuantityProblem& q, std::vector<std::string>& out) {
  std::string text = q.write_part ? "write quantity " : "quantity ";
  append_uint(text, q.found);
  text += " outside the specification's ";
  append_uint(text, q.min);
  text += '-';
  append_uint(text, q.max);
  out.push_back(std::move(text));
}

void add_exception(const SessionFrame& f, std::vector<std::string>& out) {
  if (f.reply_kind == ReplyKind::HybridError) {
    out.emplace_back("error reply");
    return;
  }
  if (f.reply_kind != ReplyKind::GslException || !f.frame->exception_code) return;
  std::string text = "exception ";
  append_hex_byte(text, *f.frame->exception_code);
  text += ": ";
  text += fc::exception_name(f.dialect, *f.frame->exception_code);
  if (*f.frame->exception_code == fc::kGatewayTargetNoResponse) {
    text += " (a timeout on the serial bus behind the gateway)";
  }
  out.push_back(std::move(text));
}

void add_value_warnings(const SessionFrame& f, std::vector<std::string>& out) {
  for (const DecodedValue& v : f.values) {
    if (v.warnings == 0 || v.has(ValueWarning::NotInMap)) continue;
    for (const ValueWarning w : kAllValueWarnings) {
      if (!v.has(w)) continue;
      std::string text(format_value_address(v, f.dialect).view());
      text += ": ";
      text += describe(w);
      out.push_back(std::move(text));
    }
  }
}

void add_decode_notes(const SessionFrame& f, std::vector<std::string>& out) {
  if (f.decode.status == DecodeStatus::StartUnknown) {
    out.emplace_back("register words without a known start address (no matching request)");
  } else if (f.decode.status == DecodeStatus::Decoded && f.decode.start_assumed) {
    out.emplace_back("start address assumed (no matching request)");
  }
}

}  // namespace

void collect_issues(const SessionFrame& f, std::vector<std::string>& out) {
  out.clear();
  if (!f.parse_error.empty()) out.push_back("malformed: " + std::string(f.parse_error));
  if (f.frame == nullptr) return;
  if (f.echo) {
    out.emplace_back("echo: the tap's adapter repeating the request before it, counted once");
    return;
  }
  // Read as a request, it echoes the pending one: a note only where the function's normal
  // reply is no echo.
  if (f.role_corrected && !reply_is_echo(f.dialect, f.frame->function)) {
    out.emplace_back("echo of a write, read as the reply");
  }
  if (!f.check.ok && f.role == Role::Response && f.request_id) {
    out.emplace_back("damaged reply: the slave answered, the line damaged the answer");
  }
  if (f.unsolicited) {
    if (f.late_by) {
      std::string text = "late reply: ";
      append_fixed(text, *f.late_by * 1e3, 1);
      text += " ms after its request, which had timed out";
      out.push_back(std::move(text));
    } else {
      out.emplace_back("unsolicited reply");
    }
  }
  if (f.duplicate) out.emplace_back("duplicate reply");
  if (f.address_conflict) {
    out.emplace_back("address conflict: a second reply to one request, with other contents");
  }
  if (f.count_mismatch) add_count_mismatch(*f.count_mismatch, out);
  if (f.quantity_problem) add_quantity_problem(*f.quantity_problem, out);
  if (f.write_count_problem) {
    std::string text = "byte count ";
    append_uint(text, f.write_count_problem->byte_count);
    text += ", the quantity written (";
    append_uint(text, f.write_count_problem->quantity);
    text += ") needs ";
    append_uint(text, f.write_count_problem->expected);
    out.push_back(std::move(text));
  }
  if (f.broadcast_not_allowed) {
    out.emplace_back("broadcast to address 0, which only writes may use: no station answers it");
  }
  if (f.dialect_changed_from) {
    std::string text = "station changed dialect: ";
    text += to_string(*f.dialect_changed_from);
    text += " before, ";
    text += to_string(f.dialect);
    text += " now";
    out.push_back(std::move(text));
  }
  add_exception(f, out);
  add_decode_notes(f, out);
  add_value_warnings(f, out);
}

std::string_view unanswered_reason(const SessionTimeout& t) {
  switch (t.kind) {
    case UnansweredKind::InputEnded:
      return "input_ended";
    case UnansweredKind::AfterLoss:
      return "data_lost";
    case UnansweredKind::DamagedRequest:
      return "damaged_request";
    case UnansweredKind::Timeout:
      break;
  }
  switch (t.timeout.reason) {
    case TimeoutReason::NextRequestFirst:
      return "next_request_first";
    case TimeoutReason::CarrierNoReply:
      return "carrier_no_reply";
    default:
      return "no_reply";
  }
}

ReadingKind reading_kind(const DecodedValue& v) {
  if (v.def == nullptr) return ReadingKind::Number;  // the word itself
  // JSON has no NaN or infinity: null, and the warning says why.
  if (!v.complete() || v.has(ValueWarning::NotFinite) || v.has(ValueWarning::NoValue) ||
      v.has(ValueWarning::NoScaleFactor)) {
    return ReadingKind::None;
  }
  switch (v.def->kind) {
    case RegisterKind::Text:
    case RegisterKind::BcdYearMonth:
    case RegisterKind::DeviceNumber:
      return ReadingKind::Text;
    default:
      return ReadingKind::Number;
  }
}

void append_value_number(std::string& out, const DecodedValue& v) {
  if (v.def == nullptr) {
    append_uint(out, v.raw);
    return;
  }
  switch (v.def->kind) {
    case RegisterKind::Number:
    case RegisterKind::Bcd:
    case RegisterKind::BcdPhaseCapacity:
      append_fixed(out, v.value, static_cast<int>(shown_decimals(v)));
      return;
    default:
      append_uint(out, v.raw);
      return;
  }
}

void append_value_words(std::string& out, const DecodedValue& v, Dialect d) {
  if (v.def == nullptr) {
    out += format_value_address(v, d).view();
    out += ' ';
  } else {
    out += v.def->name;
    out += ' ';
  }
  pvtap::append_value_text(out, v);
}

std::string latest_value_name(const LatestValue& v) {
  if (v.coil != nullptr) return std::string(v.coil->name);
  if (v.value.def != nullptr) return std::string(v.value.def->name);
  return std::string(table_name(v.table));
}

std::string latest_value_text(const LatestValue& v) {
  if (is_bit_table(v.table)) return v.value.raw != 0 ? "on" : "off";
  std::string text = format_value(v.value);
  if (v.value.def == nullptr) {
    text += " (";
    append_uint(text, v.value.raw);
    text += ')';
  }
  return text;
}

std::string inferred_address(const InferredBlock& b, const InferredValue& v) {
  const auto address = static_cast<std::uint16_t>(b.start + v.offset * address_step(b.dialect));
  return std::string(format_register_address(b.dialect, address).view());
}

std::string inferred_type(const InferredValue& v) {
  std::string t(to_string(v.kind));
  if (v.words == 2) t += v.order == WordOrder::HighFirst ? " high word first" : " low word first";
  if (v.kind == InferredKind::Text) {
    t += ", ";
    append_uint(t, v.words);
    t += " words";
  }
  if (v.counter) t += " counter";
  if (v.constant && v.kind != InferredKind::Unused) t += " constant";
  return t;
}

std::string inferred_reading(const InferredValue& v) {
  if (v.kind == InferredKind::Text) return "\"" + v.text + "\"";
  if (v.kind == InferredKind::Unused) return "-";
  const int decimals = v.kind == InferredKind::Float32 ? 3 : 0;
  std::string text;
  if (v.kind == InferredKind::Bits) {
    text = "0x";
    static constexpr char kHex[] = "0123456789ABCDEF";
    const auto raw = static_cast<unsigned>(v.last);
    for (int shift = 12; shift >= 0; shift -= 4) text += kHex[(raw >> shift) & 0xFu];
    return text;
  }
  append_fixed(text, v.last, decimals);
  if (!v.constant) {
    text += " (";
    append_fixed(text, v.min, decimals);
    text += "..";
    append_fixed(text, v.max, decimals);
    text += ')';
  }
  return text;
}

std::string function_text(Dialect d, std::uint8_t function) {
  std::string text;
  append_function(text, d, function);
  return text;
}

void append_function(std::string& out, Dialect d, std::uint8_t function) {
  out += fc::function_name(d, function);
  out += " (";
  append_hex_byte(out, function);
  out += ')';
}

std::string answering_patterns(const StationSummary& s) {
  if (s.latency.count == 0) return "the capture has no times to tell their replies apart by";
  std::string text = "its first replies came ";
  append_fixed(text, s.latency.p50 * 1e3, 1);
  text += " ms after their request (median), the other ones ";
  append_fixed(text, s.address_conflict_latency * 1e3, 1);
  text += " ms (mean)";
  return text;
}

std::string timeouts_explained(const BusReport& b) {
  if (b.timeouts == 0) return "none";
  std::string o = std::to_string(b.timeouts);
  o += b.timeouts == 1 ? " good request its station did not answer within --timeout"
                       : " good requests their station did not answer within --timeout";
  const char* sep = ": ";
  const auto part = [&](std::uint64_t n, const char* one, const char* many) {
    if (n == 0) return;
    o += sep;
    o += std::to_string(n);
    o += n == 1 ? one : many;
    sep = ", ";
  };
  part(b.timeouts_by_reason[0], " met silence until the timeout ran out",
       " met silence until the timeout ran out");
  part(b.timeouts_by_reason[1], " was cut short by the master's next request",
       " were cut short by the master's next request");
  return o;
}

}  // namespace pvtap::analyzer
