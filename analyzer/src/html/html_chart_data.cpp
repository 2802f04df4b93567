// The charts' data: lanes, bucketed counts and values, marks. Buckets are written as
// [index, ...] pairs, only where something happened; the page turns indices into times.
#include "html/html_chart_data.h"

#include <algorithm>
#include <map>
#include <set>

#include "formatting/csv_text.h"
#include "formatting/json_writer.h"
#include "formatting/number_text.h"
#include "html/html_sections.h"
#include "pvtap/codec/function_codes.h"
#include "report/frame_findings.h"
#include "report/poll_block_text.h"
#include "report/report_line.h"

namespace pvtap::analyzer {
namespace {

constexpr std::array<std::string_view, kMarkKinds> kMarkNames = {
    "damaged", "timeout", "unanswered_damaged", "exception", "unsolicited", "duplicate",
    "noise",   "gap",     "collision"};

void optional_number(JsonWriter& w, const std::optional<std::uint16_t>& v) {
  if (v) {
    w.uint(*v);
  } else {
    w.null();
  }
}

// [[index,...],...]: one row per bucket that saw something, its fields after the index
// written by `fields`.
template <typename Fields>
void bucket_rows(JsonWriter& w, const BucketSeries& s, Fields fields) {
  w.begin_array();
  for (std::size_t i = 0; i < s.buckets().size(); ++i) {
    const Bucket& b = s.buckets()[i];
    if (b.count == 0) continue;
    w.begin_array();
    w.uint(i);
    fields(b);
    w.end_array();
  }
  w.end_array();
}

// [[index,count],...] of a counting series.
void counts(JsonWriter& w, const BucketSeries& s) {
  bucket_rows(w, s, [&w](const Bucket& b) { w.uint(b.count); });
}

// [[index,sum],...].
void sums(JsonWriter& w, const BucketSeries& s) {
  bucket_rows(w, s, [&w](const Bucket& b) { w.fixed(b.sum, 0); });
}

// [[index,min,last,max],...] scaled by `factor`, with `decimals` digits.
void ranges(JsonWriter& w, const BucketSeries& s, double factor, int decimals, bool mean) {
  bucket_rows(w, s, [&](const Bucket& b) {
    w.fixed(b.min * factor, decimals);
    w.fixed((mean ? b.sum / b.count : b.last) * factor, decimals);
    w.fixed(b.max * factor, decimals);
  });
}

std::string lane_label(const AuditReport& r, const Lane& lane) {
  std::string label;
  if (r.buses.size() > 1 && !lane.bus.empty()) {
    label.append(lane.bus);
    label += ' ';
  }
  if (lane.station) {
    label += "st ";
    append_uint(label, *lane.station);
  } else {
    label += "bus";
  }
  return label;
}

void lanes(JsonWriter& w, const AuditReport& r, const Timeline& t) {
  w.key("lanes");
  w.begin_array();
  for (const Lane& lane : t.lanes) {
    w.begin_object();
    w.field("label", lane_label(r, lane));
    w.key("requests");
    counts(w, lane.requests);
    w.key("replies");
    counts(w, lane.replies);
    w.key("latency");
    ranges(w, lane.latency, 1e3, 3, true);
    w.key("histogram");
    w.begin_array();
    for (const auto bin : lane.latency_bins) w.uint(bin);
    w.end_array();
    w.end_object();
  }
  w.end_array();
}

// [time,lane,"dialect",function,request,start,count,detail], null where a mark has none.
void mark(JsonWriter& w, const AuditReport& r, const Mark& m) {
  w.begin_array();
  w.fixed(m.time, 6);
  w.uint(m.lane);
  w.plain_string(to_string(m.dialect));
  if (m.has_function) {
    w.uint(m.function);
  } else {
    w.null();
  }
  w.uint(m.is_request ? 1u : 0u);
  if (m.start) {
    w.string(start_address_text(r.settings, m.dialect, m.start));
  } else {
    w.null();
  }
  optional_number(w, m.count);
  w.uint(m.detail);
  w.end_array();
}

void marks(JsonWriter& w, const AuditReport& r, const Timeline& t) {
  w.key("marks");
  w.begin_object();
  for (std::size_t k = 0; k < kMarkKinds; ++k) {
    w.key_text(kMarkNames[k]);
    w.begin_array();
    for (const Mark& m : t.marks) {
      if (static_cast<std::size_t>(m.kind) == k) mark(w, r, m);
    }
    w.end_array();
  }
  w.end_object();
  w.key("marks_dropped");
  w.begin_object();
  for (std::size_t k = 0; k < kMarkKinds; ++k) {
    w.key_text(kMarkNames[k]);
    w.uint(t.marks_dropped[k]);
  }
  w.end_object();
}

// The names of the functions the marks name, as "dialect function": "name (0x03)".
void function_names(JsonWriter& w, const Timeline& t) {
  std::set<std::pair<Dialect, std::uint8_t>> seen;
  for (const Mark& m : t.marks) {
    if (m.has_function) seen.insert({m.dialect, m.function});
  }
  w.key("functions");
  w.begin_object();
  for (const auto& [dialect, function] : seen) {
    std::string key(to_string(dialect));
    key += ' ';
    append_uint(key, function);
    w.key_text(key);
    std::string name;
    append_function(name, dialect, function);
    w.string(name);
  }
  w.end_object();
}

void loads(JsonWriter& w, const Timeline& t) {
  w.key("loads");
  w.begin_array();
  for (const BusLoad& l : t.loads) {
    w.begin_object();
    w.field("bus", l.bus);
    w.key("to_slave");
    sums(w, l.to_slave);
    w.key("from_slave");
    sums(w, l.from_slave);
    w.key("unknown");
    sums(w, l.unknown);
    w.end_object();
  }
  w.end_array();
}

bool wanted(const ValueSeries& s, const HtmlOptions& options) {
  if (options.plot_keys.empty()) return s.changed();
  return std::find(options.plot_keys.begin(), options.plot_keys.end(), s.key) !=
         options.plot_keys.end();
}

// Numbers chart by unit; enums, bits and raw words as step lanes of their own; words no map
// names in a chart of their own.
std::string group_of(const ValueSeries& s) {
  if (s.def == nullptr) return "unmapped words";
  switch (s.def->kind) {
    case RegisterKind::Enum:
    case RegisterKind::Bits:
    case RegisterKind::Raw:
      return "states";
    default:
      return s.def->unit.empty() ? "no unit" : std::string(s.def->unit);
  }
}

std::string series_label(const AuditReport& r, const Timeline& t, const ValueSeries& s) {
  std::string label = lane_label(r, t.lanes[s.lane]);
  label += ' ';
  if (s.def == nullptr) {
    label += table_name(s.table);
    label += ' ';
    label += s.address;
  } else {
    label.append(s.def->key);
  }
  if (s.def != nullptr && s.instance > 0) {
    label += '[';
    append_uint(label, s.instance);
    label += ']';
  }
  return label;
}

void value_series(JsonWriter& w, const AuditReport& r, const Timeline& t, const ValueSeries& s) {
  w.begin_object();
  w.field("lane", s.lane);
  w.field("label", series_label(r, t, s));
  w.field("key", s.key);
  if (s.def == nullptr) {
    w.field("name", std::string(table_name(s.table)) + " " + s.address);
  } else {
    w.field("name", s.def->name);
  }
  w.field("address", s.address);
  w.field_plain("dialect", to_string(s.dialect));
  w.field("unit", s.def != nullptr ? s.def->unit : std::string_view{});
  w.field_bool("step", group_of(s) == "states");
  w.key("points");
  const bool scaled = s.def != nullptr &&
                      (s.def->kind == RegisterKind::Number || s.def->kind == RegisterKind::Bcd ||
                       s.def->kind == RegisterKind::BcdPhaseCapacity);
  // A value scaled by a scale factor register has the digits the factor gives, which the map
  // does not know: up to 10^-3, as SunSpec devices send them.
  const int digits = !scaled                     ? 0
                     : s.def->has_scale_factor() ? std::max(3, int{s.def->decimals})
                                                 : s.def->decimals;
  ranges(w, s.points, 1.0, digits, false);
  w.end_object();
}

void values(JsonWriter& w, const AuditReport& r, const Timeline& t, const HtmlOptions& options) {
  std::map<std::string, std::vector<const ValueSeries*>> groups;
  for (const ValueSeries& s : t.values) {
    if (wanted(s, options)) groups[group_of(s)].push_back(&s);
  }
  // Whether --plot chose the registers: then no chart means none of them was read, not that
  // nothing changed.
  w.field_bool("plot_chosen", !options.plot_keys.empty());
  w.key("values");
  w.begin_array();
  for (const auto& [group, members] : groups) {
    w.begin_object();
    w.field("group", group);
    w.key("series");
    w.begin_array();
    for (const ValueSeries* s : members) value_series(w, r, t, *s);
    w.end_array();
    w.end_object();
  }
  w.end_array();
}

// The silence histograms: edges in ms, a count per bucket (one more than the edges).
// Microseconds resolve every edge: the lowest is an eighth of a character (13 us at 9600).
void milliseconds(JsonWriter& w, double seconds) {
  w.fixed(seconds * 1e3, 6);
}

void histogram(JsonWriter& w, JsonKey key, const SilenceHistogram& h) {
  w.key(key);
  w.begin_object();
  w.key("edges_ms");
  w.begin_array();
  for (const double edge : h.edges()) milliseconds(w, edge);
  w.end_array();
  w.key("counts");
  w.begin_array();
  for (const auto count : h.counts()) w.uint(count);
  w.end_array();
  w.end_object();
}

void bus_silences(JsonWriter& w, const BusFindings& bus) {
  const BusGapReport& g = bus.report.timing.bus;
  w.begin_object();
  w.field("bus", bus.name.empty() ? std::string_view("serial") : std::string_view(bus.name));
  w.key("t15_ms");
  milliseconds(w, g.t15);
  w.key("t35_ms");
  milliseconds(w, g.t35);
  w.key("char_ms");
  milliseconds(w, g.inner_silences->char_time());
  histogram(w, "inner", *g.inner_silences);
  histogram(w, "between", *g.frame_silences);
  w.end_object();
}

}  // namespace

void append_chart_data_json(std::string& o, const AuditReport& r, const Timeline& t,
                            const HtmlOptions& options) {
  JsonWriter w(o);
  w.begin_object();
  w.field_bool("has_timestamps", r.settings.has_timestamps);
  w.field_bool("wall_clock", r.settings.time_base == TimeBase::WallClock);
  w.field_fixed("start", t.start, 6);
  w.field_fixed("bucket", t.bucket_width, 6);
  lanes(w, r, t);
  marks(w, r, t);
  function_names(w, t);
  loads(w, t);
  values(w, r, t, options);
  write_silence_data_json(w, r);
  w.end_object();
}

bool has_silence_histograms(const BusReport& bus) {
  const BusGapReport& g = bus.timing.bus;
  return g.measurable && g.inner_silences && g.frame_silences;
}

void write_silence_data_json(JsonWriter& w, const AuditReport& r) {
  w.key("silences");
  w.begin_array();
  for (const BusFindings& bus : r.buses) {
    if (has_silence_histograms(bus.report)) bus_silences(w, bus);
  }
  w.end_array();
}

}  // namespace pvtap::analyzer
