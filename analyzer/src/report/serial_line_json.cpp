// A logic-analyzer bus's serial line in the summary: "serial":{...},"line":{...}.
#include "formatting/json_writer.h"
#include "report/serial_line_report.h"

namespace pvtap::analyzer {
namespace {

// "turnaround":[{"driver":"DE_1","station":1,"frames":9,"release_us":{...},"truncated":0}]
void write_turnarounds(JsonWriter& w, const std::vector<DriverTurnaround>& list) {
  w.key("turnaround");
  w.begin_array();
  for (const DriverTurnaround& t : list) {
    w.begin_object();
    w.field("driver", t.driver);
    w.field("station", t.station);
    w.field("frames", t.frames);
    w.key("release_us");
    w.begin_object();
    w.field_fixed("min", t.min_us, 1);
    w.field_fixed("mean", t.mean_us, 1);
    w.field_fixed("max", t.max_us, 1);
    w.end_object();
    w.field("truncated", t.truncated);
    w.end_object();
  }
  w.end_array();
}

}  // namespace

void write_serial_line_json(JsonWriter& w, const SerialLineReport& s) {
  w.key("serial");
  w.begin_object();
  w.field("baud", s.baud);
  if (s.measured) {
    w.field_fixed("measured_baud", s.measured_baud, 1);
    w.field_fixed("deviation_percent", s.deviation * 100, 2);
  }
  w.field("parity", s.parity);
  w.field("data_bits", s.data_bits);
  w.field("stop_bits", s.stop_bits);
  w.field_bool("inverted", s.inverted);
  w.field_bool("detected", s.detected);
  w.field("channel", s.channel);
  w.end_object();
  if (!s.has_line_errors) return;
  w.key("line");
  w.begin_object();
  w.field("framing_errors", s.framing_errors);
  w.field("parity_errors", s.parity_errors);
  w.field("breaks", s.breaks);
  w.field("driver_glitches", s.driver_glitches);
  if (s.measured) w.field("clock_deviations", s.clock_deviations);
  w.end_object();
  if (!s.turnarounds.empty()) write_turnarounds(w, s.turnarounds);
}

}  // namespace pvtap::analyzer
