// The silence histograms as JSON: edges in ms, a count per bucket (one more than the edges).
#include "html/html_silence_data.h"

#include "formatting/json_text.h"
#include "formatting/number_text.h"

namespace pvtap::analyzer {
namespace {

// Microseconds resolve every edge: the lowest is an eighth of a character (13 us at 9600).
void milliseconds(std::string& o, double seconds) {
  append_fixed(o, seconds * 1e3, 6);
}

void histogram(std::string& o, const char* key, const SilenceHistogram& h) {
  append_json_key(o, key);
  o += "{\"edges_ms\":[";
  for (std::size_t i = 0; i < h.edges().size(); ++i) {
    if (i > 0) o += ',';
    milliseconds(o, h.edges()[i]);
  }
  o += "],\"counts\":[";
  for (std::size_t i = 0; i < h.counts().size(); ++i) {
    if (i > 0) o += ',';
    append_uint(o, h.counts()[i]);
  }
  o += "]}";
}

void bus_silences(std::string& o, const BusFindings& bus) {
  const BusGapReport& g = bus.report.timing.bus;
  o += "{\"bus\":";
  append_json_string(o, bus.name.empty() ? "serial" : bus.name);
  append_json_key(o, "t15_ms");
  milliseconds(o, g.t15);
  append_json_key(o, "t35_ms");
  milliseconds(o, g.t35);
  append_json_key(o, "char_ms");
  milliseconds(o, g.inner_silences->char_time());
  histogram(o, "inner", *g.inner_silences);
  histogram(o, "between", *g.frame_silences);
  o += '}';
}

}  // namespace

bool has_silence_histograms(const BusReport& bus) {
  const BusGapReport& g = bus.timing.bus;
  return g.measurable && g.inner_silences && g.frame_silences;
}

void append_silence_data_json(std::string& o, const AuditReport& r) {
  o += ",\"silences\":[";
  bool first = true;
  for (const BusFindings& bus : r.buses) {
    if (!has_silence_histograms(bus.report)) continue;
    if (!first) o += ',';
    first = false;
    bus_silences(o, bus);
  }
  o += ']';
}

}  // namespace pvtap::analyzer
