// The --values rows in their three formats. Rows are built straight into the output buffer:
// a day of polling is millions of values.
#include "writers/values_writer.h"

#include <string>

#include "formatting/csv_text.h"
#include "formatting/json_writer.h"
#include "formatting/number_text.h"
#include "pvtap/registers/register_format.h"
#include "report/frame_findings.h"
#include "report/report_line.h"

namespace pvtap::analyzer {
namespace {

constexpr std::string_view kCsvHeader = "ts,bus,station,dialect,register,key,name,value,unit\n";

// ValueRow: what every row names besides the reading itself.
struct ValueRow {
  const EventContext& context;
  const SessionFrame& frame;
  const DecodedValue& value;
  std::uint8_t station() const { return frame.frame != nullptr ? frame.frame->station : 0; }
  // The map's key, or for a word no map names its table and address ("input_reg_0x0002"), so
  // that holding and input registers stay apart.
  UnmappedKey key_buffer() const {
    if (value.def != nullptr || frame.frame == nullptr) return {};
    return unmapped_key(unmapped_table(frame.dialect, frame.frame->function), value.address);
  }
};

void append_csv_row(std::string& o, const ValueRow& r, std::string& scratch) {
  if (r.context.has_timestamps) append_fixed(o, r.frame.start_time, 6);
  o += ',';
  append_csv_field(o, r.context.bus);
  o += ',';
  append_uint(o, r.station());
  o += ',';
  o += to_string(r.frame.dialect);
  o += ',';
  o += format_value_address(r.value, r.frame.dialect).view();
  o += ',';
  const UnmappedKey unmapped = r.key_buffer();
  append_csv_field(o, r.value.def != nullptr ? r.value.key() : unmapped.view());
  o += ',';
  append_csv_field(o, r.value.name());
  o += ',';
  switch (reading_kind(r.value)) {
    case ReadingKind::Number:
      append_value_number(o, r.value);
      break;
    case ReadingKind::Text:
      scratch.clear();
      append_value_text(scratch, r.value);
      append_csv_field(o, scratch);
      break;
    case ReadingKind::None:
      break;
  }
  o += ',';
  append_csv_field(o, r.value.unit());
  o += '\n';
}

void string_or_null(JsonWriter& w, JsonKey name, std::string_view text) {
  if (text.empty()) {
    w.field_null(name);
  } else {
    w.field(name, text);
  }
}

void append_jsonl_row(std::string& o, const ValueRow& r, std::string& scratch) {
  JsonWriter w(o);
  w.begin_object();
  w.key("ts");
  if (r.context.has_timestamps) {
    w.fixed(r.frame.start_time, 6);
  } else {
    w.null();
  }
  string_or_null(w, "bus", r.context.bus);
  w.field("station", r.station());
  w.field_plain("dialect", to_string(r.frame.dialect));
  w.field_plain("register", format_value_address(r.value, r.frame.dialect).view());
  const UnmappedKey unmapped = r.key_buffer();
  string_or_null(w, "key", r.value.def != nullptr ? r.value.key() : unmapped.view());
  string_or_null(w, "name", r.value.name());
  w.key("value");
  if (reading_kind(r.value) == ReadingKind::Number) {
    append_value_number(w.value_out(), r.value);
  } else if (reading_kind(r.value) == ReadingKind::Text) {
    scratch.clear();
    append_value_text(scratch, r.value);
    w.string(scratch);
  } else {
    w.null();
  }
  string_or_null(w, "unit", r.value.unit());
  w.end_object();
  o += '\n';
}

// Line protocol escapes commas, equals signs and spaces in tag values with a backslash, and
// nothing else: InfluxDB keeps any other backslash as it is, so a doubled one would be stored
// doubled.
void append_influx_tag(std::string& o, std::string_view name, std::string_view value) {
  o += ',';
  o += name;
  o += '=';
  for (const char ch : value) {
    if (ch == ',' || ch == '=' || ch == ' ') o += '\\';
    o += ch;
  }
}

// The microseconds of the ts column, digit for digit, as nanoseconds (a double cannot carry
// nanoseconds of an epoch, and its product with 1e6 may round the other way than the printed
// ts); without the leading zeros of a time under a second, which are no integer's digits.
void append_influx_time(std::string& o, double seconds) {
  const std::size_t at = o.size();
  append_fixed(o, seconds, 6);
  o.erase(o.find('.', at), 1);
  const std::size_t digits = o[at] == '-' ? at + 1 : at;
  const std::size_t first = o.find_first_not_of('0', digits);
  if (first == std::string::npos) {
    o.resize(at);
    o += '0';
    return;
  }
  o.erase(digits, first - digits);
  o += "000";
}

void append_influx_row(std::string& o, const ValueRow& r) {
  // Line protocol fields are numbers here; a word outside the map is tagged with its table
  // and address.
  if (reading_kind(r.value) != ReadingKind::Number) return;
  const UnmappedKey unmapped = r.key_buffer();
  const std::string_view key = r.value.def != nullptr ? r.value.key() : unmapped.view();
  if (key.empty()) return;
  o += "pvtap";
  if (!r.context.bus.empty()) append_influx_tag(o, "bus", r.context.bus);
  o += ",station=";
  append_uint(o, r.station());
  o += ",dialect=";
  o += to_string(r.frame.dialect);
  append_influx_tag(o, "key", key);
  o += " value=";
  append_value_number(o, r.value);
  if (r.context.has_timestamps) {
    o += ' ';
    append_influx_time(o, r.frame.start_time);
  }
  o += '\n';
}

class ValuesWriter : public EventWriter {
 public:
  ValuesWriter(ValuesFormat format, OutputStream& out) : format_(format), out_(out) {}

  void begin() override {
    if (format_ == ValuesFormat::Csv) out_.write(kCsvHeader);
  }

  void frame(const EventContext& c, const SessionFrame& f) override {
    if (!frame_feeds_values(f)) return;
    std::string& o = out_.buffer();
    for (const DecodedValue& v : f.values) {
      const ValueRow row{c, f, v};
      switch (format_) {
        case ValuesFormat::Csv:
          append_csv_row(o, row, scratch_);
          break;
        case ValuesFormat::Jsonl:
          append_jsonl_row(o, row, scratch_);
          break;
        case ValuesFormat::Influx:
          append_influx_row(o, row);
          break;
      }
    }
    out_.done();
  }
  void timeout(const EventContext&, const SessionTimeout&) override {}
  void noise(const EventContext&, const SessionNoise&) override {}
  void gap(const EventContext&, const SessionGap&) override {}

 private:
  ValuesFormat format_;
  OutputStream& out_;
  std::string scratch_;
};

}  // namespace

bool frame_feeds_values(const SessionFrame& f) {
  return f.role == Role::Response && f.check.ok && f.values_trusted && f.placed_by.has_value();
}

std::unique_ptr<EventWriter> make_values_writer(ValuesFormat format, OutputStream& out) {
  return std::make_unique<ValuesWriter>(format, out);
}

}  // namespace pvtap::analyzer
