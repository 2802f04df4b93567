// The silence histograms as JSON: edges in ms, a count per bucket (one more than the edges).
#include "html/html_silence_data.h"

#include "formatting/json_writer.h"

namespace pvtap::analyzer {
namespace {

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
