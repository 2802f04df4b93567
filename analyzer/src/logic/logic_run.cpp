// run_logic_audit: buses from the plan, the recording read through UartTap.
#include "logic/logic_run.h"

#include <cstdio>

#include "logic/uart_tap.h"
#include "pvtap/session/carrier_timing.h"

namespace pvtap::analyzer {
namespace {

// A bus read at the line's own rate and character length, timed by the sample clock.
BusSessionOptions logic_bus_options(const Pipeline& pipeline, const DetectedLine& line,
                                    double sample_rate) {
  BusSessionOptions o = pipeline.bus_options(InputKind::Serial);
  o.reassembler.baud = line.baud.baud;
  o.reassembler.bits_per_char = line.line.format.bits_per_char();
  apply_sample_clock(sample_rate, o);
  return o;
}

std::string link_text(const LogicPlan& plan) {
  char text[96];
  std::snprintf(text, sizeof text, "sigrok logic, %zu UART channel%s at %g MS/s",
                plan.channels.size(), plan.channels.size() == 1 ? "" : "s", plan.sample_rate / 1e6);
  return text;
}

}  // namespace

LogicRun run_logic_audit(const LogicPlan& plan, Pipeline& pipeline, EventWriter& events) {
  std::vector<TappedChannel> tapped;
  for (const ProbedChannel& p : plan.channels) {
    BusSession& bus =
        pipeline.add_bus(p.channel.name, logic_bus_options(pipeline, *p.line, plan.sample_rate));
    tapped.push_back(TappedChannel{p.channel, *p.line, &bus});
  }
  UartTap tap(std::move(tapped), plan.drivers, plan.sample_rate, events);
  LogicRun run;
  run.error = read_logic_file(plan.path, tap);
  tap.finish();
  run.end_time = tap.end_time();
  pipeline.finish(run.end_time);
  run.lines = tap.lines();
  run.input.path = plan.path;
  run.input.link_type = link_text(plan);
  run.input.records = tap.chunks();
  run.input.truncated = !run.error.empty();
  run.input.error = run.error;
  return run;
}

void add_serial_lines(const LogicRun& run, AuditReport& report) {
  for (BusFindings& bus : report.buses) {
    for (const SerialLineReport& line : run.lines) {
      if (line.channel == bus.name) bus.serial = line;
    }
  }
  if (!run.lines.empty()) report.settings.baud = run.lines.front().baud;
  report.inputs.push_back(run.input);
}

}  // namespace pvtap::analyzer
