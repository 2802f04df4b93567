#include "diff/diff_writers.h"

#include <array>
#include <cmath>
#include <utility>

#include "formatting/json_writer.h"
#include "formatting/number_text.h"
#include "html/html_assets.h"
#include "html/html_text.h"

namespace pvtap::analyzer {
namespace {

// Every key of a difference with its words: the one place they are named.
constexpr std::array<std::pair<std::string_view, std::string_view>, 14> kWords{{
    {"bus", "bus"},
    {"station", "station"},
    {"noise_bytes_per_1000_bytes", "noise bytes per 1000 bytes"},
    {"unattributed_bad_checks_per_1000_frames", "bad checks of no station per 1000 frames"},
    {"requests_per_minute", "requests per minute"},
    {"bad_checks_per_1000_frames", "bad checks per 1000 frames"},
    {"timeouts_per_1000_requests", "timeouts per 1000 requests"},
    {"exceptions_per_1000_requests", "exceptions per 1000 requests"},
    {"latency_p50", "latency p50"},
    {"latency_p95", "latency p95"},
    {"poll_block", "poll block"},
    {"poll_period", "poll period"},
    {"poll_jitter", "poll jitter"},
    {"register_range", "register"},
}};

std::string number_or_none(const std::optional<double>& value) {
  if (!value) return "none";
  std::string o;
  append_fixed(o, *value, 2);
  return o;
}

std::uint64_t frames_of(const DiffSide& side) {
  std::uint64_t frames = 0;
  for (const BusFindings& bus : side.report.buses) frames += bus.report.bytes.frames;
  return frames;
}

// "a.pcap (1 bus, 2411 frames, 300.0 s)".
std::string side_text(const std::string& label, const DiffSide& side) {
  std::string o = label + " (";
  append_uint(o, side.report.buses.size());
  o += side.report.buses.size() == 1 ? " bus, " : " buses, ";
  append_uint(o, frames_of(side));
  o += " frames";
  if (const auto span = side.report.time_span()) {
    o += ", ";
    append_fixed(o, span->seconds(), 1);
    o += " s";
  }
  return o + ")";
}

// "-86.79, -100 %", or "+12.5, from 0".
std::string change_text(double before, double after) {
  const double delta = after - before;
  std::string o = delta >= 0 ? "+" : "";
  append_fixed(o, delta, 2);
  if (before == 0) return o + ", from 0";
  o += delta >= 0 ? ", +" : ", -";
  append_fixed(o, std::fabs(delta) / std::fabs(before) * 100, 0);
  return o + " %";
}

std::size_t uncounted(const DiffResult& r) {
  return r.differences.size() - r.counted();
}

std::string what_text(const Difference& d) {
  std::string o(difference_words(d.what));
  if (!d.detail.empty()) o += " " + d.detail;
  return o;
}

void json_number(JsonWriter& w, JsonKey key, const std::optional<double>& value) {
  w.key(key);
  if (value) {
    w.fixed(*value, 3);
  } else {
    w.null();
  }
}

void side_json(JsonWriter& w, JsonKey key, const std::string& label, const DiffSide& side) {
  w.key(key);
  w.begin_object();
  w.field("files", label);
  w.field("buses", side.report.buses.size());
  w.field("frames", frames_of(side));
  const auto span = side.report.time_span();
  json_number(w, "seconds", span ? std::optional(span->seconds()) : std::nullopt);
  w.end_object();
}

struct NamedThreshold {
  JsonKey name;
  double value;
};

void thresholds_json(JsonWriter& w, const DiffThresholds& t) {
  w.key("thresholds");
  const NamedThreshold figures[] = {
      {"noise_sigmas", t.noise_sigmas},  {"rate_per_1000", t.rate_per_1000},
      {"rate_percent", t.rate_percent},  {"requests_percent", t.requests_percent},
      {"latency_ms", t.latency_ms},      {"latency_percent", t.latency_percent},
      {"period_ms", t.period_ms},        {"period_percent", t.period_percent},
      {"jitter_ms", t.jitter_ms},        {"jitter_percent", t.jitter_percent},
      {"value_percent", t.value_percent}};
  w.begin_object();
  for (const auto& [name, value] : figures) w.field_fixed(name, value, 3);
  w.field_bool("count_values", t.count_values);
  w.end_object();
}

void html_cell(std::string& o, std::string_view text) {
  o += "<td>";
  append_html_escaped(o, text);
  o += "</td>";
}

}  // namespace

std::string_view difference_words(std::string_view what) {
  for (const auto& [key, words] : kWords) {
    if (key == what) return words;
  }
  return what;
}

void append_diff_text(std::string& o, const DiffReport& r) {
  o += "before: " + side_text(r.before_label, *r.before) + "\n";
  o += "after:  " + side_text(r.after_label, *r.after) + "\n";
  const std::string* bus = nullptr;
  std::optional<std::optional<std::uint8_t>> station;
  for (const Difference& d : r.result.differences) {
    if (bus == nullptr || *bus != d.bus) {
      o += "\nbus " + d.bus + "\n";
      bus = &d.bus;
      station.reset();
    }
    if (!station || *station != d.station) {
      station = d.station;
      if (d.station) {
        o += "  station ";
        append_uint(o, *d.station);
        o += "\n";
      }
    }
    o += d.station ? "    " : "  ";
    o += what_text(d) + ": ";
    // A figure of both sides: before -> after, the change, and why it counts; a thing of one
    // side, or a register's ranges: why alone.
    if (d.before && d.after && d.what != "register_range") {
      o += number_or_none(d.before) + " -> " + number_or_none(d.after);
      if (!d.unit.empty()) o += " " + d.unit;
      o += " (" + change_text(*d.before, *d.after) + "): ";
    }
    o += d.reason;
    if (!d.counted) o += "; not counted without --count-values";
    o += "\n";
  }
  o += "\n";
  const std::size_t counted = r.result.counted();
  if (counted == 0) {
    o += "no differences beyond the noise of sampling";
  } else {
    append_uint(o, counted);
    o += counted == 1 ? " difference" : " differences";
    o += " beyond the noise of sampling";
  }
  if (const std::size_t more = uncounted(r.result); more > 0) {
    o += " (and ";
    append_uint(o, more);
    o += more == 1 ? " register range move" : " register range moves";
    o += ", not counted without --count-values)";
  }
  o += "\n";
}

void append_diff_jsonl(std::string& o, const DiffReport& r) {
  for (const Difference& d : r.result.differences) {
    JsonWriter w(o);
    w.begin_object();
    w.field_plain("type", "difference");
    w.field("bus", d.bus);
    w.key("station");
    if (d.station) {
      w.uint(*d.station);
    } else {
      w.null();
    }
    w.field("what", d.what);
    w.field("detail", d.detail);
    json_number(w, "before", d.before);
    json_number(w, "after", d.after);
    w.field("unit", d.unit);
    w.field("reason", d.reason);
    w.field_bool("counted", d.counted);
    w.end_object();
    o += '\n';
  }
  JsonWriter w(o);
  w.begin_object();
  w.field_plain("type", "summary");
  w.field("differences", r.result.counted());
  w.field("not_counted", uncounted(r.result));
  side_json(w, "before", r.before_label, *r.before);
  side_json(w, "after", r.after_label, *r.after);
  thresholds_json(w, r.thresholds);
  w.end_object();
  o += '\n';
}

void append_diff_html(std::string& o, const DiffReport& r) {
  o += "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  o += "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n";
  o += "<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; "
       "style-src 'unsafe-inline'\">\n<title>pvtap diff: ";
  append_html_escaped(o, r.before_label + " -> " + r.after_label);
  o += "</title>\n<style>\n";
  o += html_assets::page_css;
  o += "\n</style>\n</head>\n<body>\n<header><h1>pvtap diff</h1>\n<p>before: ";
  append_html_escaped(o, side_text(r.before_label, *r.before));
  o += "<br>after: ";
  append_html_escaped(o, side_text(r.after_label, *r.after));
  o += "</p></header>\n<main>\n<section id=\"differences\"><h2>";
  const std::size_t counted = r.result.counted();
  if (counted == 0) {
    o += "No differences beyond the noise of sampling";
  } else {
    append_uint(o, counted);
    o += counted == 1 ? " difference" : " differences";
    o += " beyond the noise of sampling";
  }
  o += "</h2>\n";
  const std::string* bus = nullptr;
  for (const Difference& d : r.result.differences) {
    if (bus == nullptr || *bus != d.bus) {
      if (bus != nullptr) o += "</tbody></table>\n";
      bus = &d.bus;
      o += "<h3>bus ";
      append_html_escaped(o, d.bus);
      o += "</h3>\n<table><thead><tr><th>station</th><th>what</th><th>before</th>"
           "<th>after</th><th>unit</th><th>why</th><th>counted</th></tr></thead><tbody>\n";
    }
    o += "<tr>";
    std::string station;
    if (d.station) append_uint(station, *d.station);
    html_cell(o, station);
    html_cell(o, what_text(d));
    html_cell(o, number_or_none(d.before));
    html_cell(o, number_or_none(d.after));
    html_cell(o, d.unit);
    html_cell(o, d.reason);
    html_cell(o, d.counted ? "yes" : "no (--count-values)");
    o += "</tr>\n";
  }
  if (bus != nullptr) o += "</tbody></table>\n";
  o += "</section>\n</main>\n</body>\n</html>\n";
}

}  // namespace pvtap::analyzer
