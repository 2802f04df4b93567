// The charts' data: lanes, bucketed counts and values, marks. Buckets are written as
// [index, ...] pairs, only where something happened; the page turns indices into times.
#include "html/html_chart_data.h"

#include <algorithm>
#include <map>
#include <set>

#include "formatting/csv_text.h"
#include "formatting/json_text.h"
#include "formatting/number_text.h"
#include "html/html_sections.h"
#include "html/html_silence_data.h"
#include "pvtap/codec/function_codes.h"
#include "report/frame_findings.h"
#include "report/poll_block_text.h"
#include "report/report_line.h"

namespace pvtap::analyzer {
namespace {

constexpr std::array<std::string_view, kMarkKinds> kMarkNames = {
    "damaged", "timeout", "unanswered_damaged", "exception", "unsolicited", "duplicate",
    "noise",   "gap",     "collision"};

void optional_number(std::string& o, const std::optional<std::uint16_t>& v) {
  if (v) {
    append_uint(o, *v);
  } else {
    o += "null";
  }
}

// [[index,...],...]: one row per bucket that saw something, its fields after the index
// written by `fields`.
template <typename Fields>
void bucket_rows(std::string& o, const BucketSeries& s, Fields fields) {
  o += '[';
  bool first = true;
  for (std::size_t i = 0; i < s.buckets().size(); ++i) {
    const Bucket& b = s.buckets()[i];
    if (b.count == 0) continue;
    if (!first) o += ',';
    first = false;
    o += '[';
    append_uint(o, i);
    fields(b);
    o += ']';
  }
  o += ']';
}

// [[index,count],...] of a counting series.
void counts(std::string& o, const BucketSeries& s) {
  bucket_rows(o, s, [&o](const Bucket& b) {
    o += ',';
    append_uint(o, b.count);
  });
}

// [[index,sum],...].
void sums(std::string& o, const BucketSeries& s) {
  bucket_rows(o, s, [&o](const Bucket& b) {
    o += ',';
    append_fixed(o, b.sum, 0);
  });
}

// [[index,min,last,max],...] scaled by `factor`, with `decimals` digits.
void ranges(std::string& o, const BucketSeries& s, double factor, int decimals, bool mean) {
  bucket_rows(o, s, [&](const Bucket& b) {
    o += ',';
    append_fixed(o, b.min * factor, decimals);
    o += ',';
    append_fixed(o, (mean ? b.sum / b.count : b.last) * factor, decimals);
    o += ',';
    append_fixed(o, b.max * factor, decimals);
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

void lanes(std::string& o, const AuditReport& r, const Timeline& t) {
  o += ",\"lanes\":[";
  for (std::size_t i = 0; i < t.lanes.size(); ++i) {
    const Lane& lane = t.lanes[i];
    if (i > 0) o += ',';
    o += "{\"label\":";
    append_json_string(o, lane_label(r, lane));
    o += ",\"requests\":";
    counts(o, lane.requests);
    o += ",\"replies\":";
    counts(o, lane.replies);
    o += ",\"latency\":";
    ranges(o, lane.latency, 1e3, 3, true);
    o += ",\"histogram\":[";
    for (std::size_t b = 0; b < lane.latency_bins.size(); ++b) {
      if (b > 0) o += ',';
      append_uint(o, lane.latency_bins[b]);
    }
    o += "]}";
  }
  o += ']';
}

void marks(std::string& o, const AuditReport& r, const Timeline& t) {
  o += ",\"marks\":{";
  for (std::size_t k = 0; k < kMarkKinds; ++k) {
    if (k > 0) o += ',';
    append_json_string(o, kMarkNames[k]);
    o += ":[";
    bool first = true;
    for (const Mark& m : t.marks) {
      if (static_cast<std::size_t>(m.kind) != k) continue;
      if (!first) o += ',';
      first = false;
      o += '[';
      append_fixed(o, m.time, 6);
      o += ',';
      append_uint(o, m.lane);
      o += ",\"";
      o += to_string(m.dialect);
      o += "\",";
      if (m.has_function) {
        append_uint(o, m.function);
      } else {
        o += "null";
      }
      o += m.is_request ? ",1," : ",0,";
      if (m.start) {
        append_json_string(o, start_address_text(r.settings, m.dialect, m.start));
      } else {
        o += "null";
      }
      o += ',';
      optional_number(o, m.count);
      o += ',';
      append_uint(o, m.detail);
      o += ']';
    }
    o += ']';
  }
  o += "},\"marks_dropped\":{";
  for (std::size_t k = 0; k < kMarkKinds; ++k) {
    if (k > 0) o += ',';
    append_json_string(o, kMarkNames[k]);
    o += ':';
    append_uint(o, t.marks_dropped[k]);
  }
  o += '}';
}

// The names of the functions the marks name, as "dialect function": "name (0x03)".
void function_names(std::string& o, const Timeline& t) {
  std::set<std::pair<Dialect, std::uint8_t>> seen;
  for (const Mark& m : t.marks) {
    if (m.has_function) seen.insert({m.dialect, m.function});
  }
  o += ",\"functions\":{";
  bool first = true;
  for (const auto& [dialect, function] : seen) {
    if (!first) o += ',';
    first = false;
    std::string key(to_string(dialect));
    key += ' ';
    append_uint(key, function);
    append_json_string(o, key);
    o += ':';
    std::string name;
    append_function(name, dialect, function);
    append_json_string(o, name);
  }
  o += '}';
}

void loads(std::string& o, const Timeline& t) {
  o += ",\"loads\":[";
  for (std::size_t i = 0; i < t.loads.size(); ++i) {
    const BusLoad& l = t.loads[i];
    if (i > 0) o += ',';
    o += "{\"bus\":";
    append_json_string(o, l.bus);
    o += ",\"to_slave\":";
    sums(o, l.to_slave);
    o += ",\"from_slave\":";
    sums(o, l.from_slave);
    o += ",\"unknown\":";
    sums(o, l.unknown);
    o += '}';
  }
  o += ']';
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

void value_series(std::string& o, const AuditReport& r, const Timeline& t, const ValueSeries& s) {
  o += "{\"lane\":";
  append_uint(o, s.lane);
  o += ",\"label\":";
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
  append_json_string(o, label);
  o += ",\"key\":";
  append_json_string(o, s.key);
  o += ",\"name\":";
  if (s.def == nullptr) {
    append_json_string(o, std::string(table_name(s.table)) + " " + s.address);
  } else {
    append_json_string(o, s.def->name);
  }
  o += ",\"address\":";
  append_json_string(o, s.address);
  o += ",\"dialect\":\"";
  o += to_string(s.dialect);
  o += "\",\"unit\":";
  append_json_string(o, s.def != nullptr ? s.def->unit : std::string_view{});
  o += ",\"step\":";
  o += group_of(s) == "states" ? "true" : "false";
  o += ",\"points\":";
  const bool scaled = s.def != nullptr &&
                      (s.def->kind == RegisterKind::Number || s.def->kind == RegisterKind::Bcd ||
                       s.def->kind == RegisterKind::BcdPhaseCapacity);
  // A value scaled by a scale factor register has the digits the factor gives, which the map
  // does not know: up to 10^-3, as SunSpec devices send them.
  const int digits = !scaled                     ? 0
                     : s.def->has_scale_factor() ? std::max(3, int{s.def->decimals})
                                                 : s.def->decimals;
  ranges(o, s.points, 1.0, digits, false);
  o += '}';
}

void values(std::string& o, const AuditReport& r, const Timeline& t, const HtmlOptions& options) {
  std::map<std::string, std::vector<const ValueSeries*>> groups;
  for (const ValueSeries& s : t.values) {
    if (wanted(s, options)) groups[group_of(s)].push_back(&s);
  }
  // Whether --plot chose the registers: then no chart means none of them was read, not that
  // nothing changed.
  o += ",\"plot_chosen\":";
  o += options.plot_keys.empty() ? "false" : "true";
  o += ",\"values\":[";
  bool first = true;
  for (const auto& [group, members] : groups) {
    if (!first) o += ',';
    first = false;
    o += "{\"group\":";
    append_json_string(o, group);
    o += ",\"series\":[";
    for (std::size_t i = 0; i < members.size(); ++i) {
      if (i > 0) o += ',';
      value_series(o, r, t, *members[i]);
    }
    o += "]}";
  }
  o += ']';
}

}  // namespace

void append_chart_data_json(std::string& o, const AuditReport& r, const Timeline& t,
                            const HtmlOptions& options) {
  o += "{\"has_timestamps\":";
  o += r.settings.has_timestamps ? "true" : "false";
  o += ",\"wall_clock\":";
  o += r.settings.time_base == TimeBase::WallClock ? "true" : "false";
  o += ",\"start\":";
  append_fixed(o, t.start, 6);
  o += ",\"bucket\":";
  append_fixed(o, t.bucket_width, 6);
  lanes(o, r, t);
  marks(o, r, t);
  function_names(o, t);
  loads(o, t);
  values(o, r, t, options);
  append_silence_data_json(o, r);
  o += '}';
}

}  // namespace pvtap::analyzer
