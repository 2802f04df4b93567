// run_logic_audit: buses from the plan, the recording read through UartTap.
#include "logic/logic_run.h"

#include <algorithm>
#include <cstdio>

#include "logic/tap/uart_tap.h"
#include "pvtap/session/timestamping.h"

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

// The line's errors are the bus's: its session counted them as they came.
void take_line_errors(const LineErrorTally& counted, SerialLineReport& line) {
  line.framing_errors = counted.framing_errors;
  line.parity_errors = counted.parity_errors;
  line.breaks = counted.breaks;
  line.driver_glitches = counted.driver_glitches;
}

}  // namespace

std::string logic_link_text(const LogicPlan& plan) {
  char text[96];
  std::snprintf(text, sizeof text, "sigrok logic, %zu UART channel%s at %g MS/s",
                plan.channels.size(), plan.channels.size() == 1 ? "" : "s", plan.sample_rate / 1e6);
  return text;
}

std::unique_ptr<UartTap> tap_planned_channels(const LogicPlan& plan, Pipeline& pipeline) {
  std::vector<TappedChannel> tapped;
  int pairs = 0;
  for (const std::vector<std::size_t>& group : plan.buses) {
    const ProbedChannel& first = plan.channels[group.front()];
    std::string name = first.channel.name;
    for (std::size_t i = 1; i < group.size(); ++i)
      name += "," + plan.channels[group[i]].channel.name;
    BusSession& bus =
        pipeline.add_bus(name, logic_bus_options(pipeline, *first.line, plan.sample_rate));
    const int pair = group.size() == 2 ? pairs++ : -1;
    for (std::size_t side = 0; side < group.size(); ++side) {
      const ProbedChannel& p = plan.channels[group[side]];
      tapped.push_back(TappedChannel{p.channel, *p.line, &bus, name, pair, side});
    }
  }
  return std::make_unique<UartTap>(std::move(tapped), plan.drivers, plan.sample_rate);
}

LogicRun run_logic_audit(const LogicPlan& plan, Pipeline& pipeline) {
  const std::unique_ptr<UartTap> owned = tap_planned_channels(plan, pipeline);
  UartTap& tap = *owned;
  LogicRun run;
  if (plan.held.whole) {
    plan.held.replay(tap);
  } else {
    // Read again at the rate the plan was made at, --samplerate's where one was given.
    run.error = read_logic_file(plan.path, tap, plan.sample_rate);
  }
  tap.finish();
  run.end_time = tap.end_time();
  pipeline.finish(run.end_time);
  run.lines = tap.lines();
  run.input.path = plan.path;
  run.input.link_type = logic_link_text(plan);
  run.input.records = tap.chunks();
  run.input.truncated = !run.error.empty();
  run.input.error = run.error;
  return run;
}

// A bus on two channels reports its requests' line (the first), with the errors of both.
void add_serial_lines(const LogicRun& run, AuditReport& report) {
  for (BusFindings& bus : report.buses) {
    for (const auto& [bus_name, line] : run.lines) {
      if (bus_name != bus.name) continue;
      if (bus.serial) {
        // Both directions of a bus off the standard rate are one clock finding, not two.
        bus.serial->clock_deviations =
            std::max(bus.serial->clock_deviations, line.clock_deviations);
      } else {
        bus.serial = line;
        bus.serial->channel = bus.name;
      }
    }
    if (bus.serial) take_line_errors(bus.report.line_errors, *bus.serial);
  }
  if (!run.lines.empty()) report.settings.baud = run.lines.front().line.baud;
  // The sample clock counts from the recording's start: no time here is a wall-clock time.
  report.settings.time_base = TimeBase::RecordingStart;
  report.inputs.push_back(run.input);
}

}  // namespace pvtap::analyzer
