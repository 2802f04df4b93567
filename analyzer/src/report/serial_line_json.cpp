// A logic-analyzer bus's serial line in the summary: "serial":{...},"line":{...}.
#include "formatting/json_text.h"
#include "formatting/number_text.h"
#include "report/serial_line_report.h"

namespace pvtap::analyzer {
namespace {

// "turnaround":[{"driver":"DE_1","station":1,"frames":9,"release_us":{...},"truncated":0}]
void append_turnarounds_json(const std::vector<DriverTurnaround>& list, std::string& o) {
  append_json_key(o, "turnaround");
  o += '[';
  for (std::size_t i = 0; i < list.size(); ++i) {
    const DriverTurnaround& t = list[i];
    o += i ? ",{\"driver\":" : "{\"driver\":";
    append_json_string(o, t.driver);
    append_json_count(o, "station", t.station);
    append_json_count(o, "frames", t.frames);
    append_json_key(o, "release_us");
    o += "{\"min\":";
    append_fixed(o, t.min_us, 1);
    append_json_key(o, "mean");
    append_fixed(o, t.mean_us, 1);
    append_json_key(o, "max");
    append_fixed(o, t.max_us, 1);
    o += '}';
    append_json_count(o, "truncated", t.truncated);
    o += '}';
  }
  o += ']';
}

}  // namespace

void append_serial_line_json(const SerialLineReport& s, std::string& o) {
  append_json_key(o, "serial");
  o += "{\"baud\":";
  append_uint(o, s.baud);
  if (s.measured) {
    append_json_key(o, "measured_baud");
    append_fixed(o, s.measured_baud, 1);
    append_json_key(o, "deviation_percent");
    append_fixed(o, s.deviation * 100, 2);
  }
  append_json_key(o, "parity");
  append_json_string(o, s.parity);
  append_json_count(o, "data_bits", s.data_bits);
  append_json_count(o, "stop_bits", s.stop_bits);
  append_json_key(o, "inverted");
  o += s.inverted ? "true" : "false";
  append_json_key(o, "detected");
  o += s.detected ? "true" : "false";
  append_json_key(o, "channel");
  append_json_string(o, s.channel);
  o += '}';
  if (!s.has_line_errors) return;
  append_json_key(o, "line");
  o += "{\"framing_errors\":";
  append_uint(o, s.framing_errors);
  append_json_count(o, "parity_errors", s.parity_errors);
  append_json_count(o, "breaks", s.breaks);
  append_json_count(o, "driver_glitches", s.driver_glitches);
  if (s.measured) append_json_count(o, "clock_deviations", s.clock_deviations);
  o += '}';
  if (!s.turnarounds.empty()) append_turnarounds_json(s.turnarounds, o);
}

}  // namespace pvtap::analyzer
