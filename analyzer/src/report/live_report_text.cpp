// The live sources in the text report: what each tap and interface went through.
#include "report/report_line.h"
#include "report/report_writers.h"

namespace pvtap::analyzer {
namespace {

unsigned long long u(std::uint64_t v) {
  return static_cast<unsigned long long>(v);
}

void latency_timer(const DeviceReport& d, std::string& o) {
  if (d.latency_timer_ms) {
    o += report_line("  USB latency timer: %d ms%s%s", *d.latency_timer_ms,
                     d.latency_note.empty() ? "" : " - ", d.latency_note.c_str());
  } else if (!d.latency_note.empty()) {
    o += report_line("  USB latency timer: %s", d.latency_note.c_str());
  }
}

void line_errors(const DeviceReport& d, std::string& o) {
  if (!d.line_errors) {
    o += report_line("  line errors: not available (%s)", d.line_errors_note.c_str());
    return;
  }
  const LineErrorCounts& e = *d.line_errors;
  o += report_line(
      "  line errors: framing %llu, parity %llu, overrun %llu, buffer overrun %llu, "
      "break %llu",
      u(e.framing), u(e.parity), u(e.overrun), u(e.buffer_overrun), u(e.breaks));
}

void device(const DeviceReport& d, std::string& o) {
  o += report_line("device: %s%s%s (%s): %llu bytes in %llu reads", d.path.c_str(),
                   d.adapter.empty() ? "" : " -> ", d.adapter.c_str(), d.line.c_str(), u(d.bytes),
                   u(d.reads));
  latency_timer(d, o);
  line_errors(d, o);
  if (d.outages > 0) {
    o += report_line("  OUTAGES: %llu, %.1f s without the device%s", u(d.outages), d.outage_seconds,
                     d.lost_at_end ? "; gone when the capture stopped" : "");
  }
  if (!d.last_error.empty()) o += report_line("  last error: %s", d.last_error.c_str());
}

void interface(const InterfaceReport& i, std::string& o) {
  o += report_line("interface: %s (%s), filter \"%s\": %llu packets", i.name.c_str(),
                   i.link_type.c_str(), i.filter.c_str(), u(i.packets));
  if (i.dropped || i.interface_dropped) {
    o += report_line("  dropped: %llu by the kernel, %llu by the interface",
                     u(i.dropped.value_or(0)), u(i.interface_dropped.value_or(0)));
  }
}

}  // namespace

void append_live_sources_text(const LiveSources& live, std::string& o) {
  if (!live.active()) return;
  o += report_line("captured live for %.1f s%s", live.seconds,
                   live.stopped_by_signal ? " (stopped by signal)" : "");
  for (const DeviceReport& d : live.devices) device(d, o);
  if (live.interface) interface(*live.interface, o);
}

}  // namespace pvtap::analyzer
