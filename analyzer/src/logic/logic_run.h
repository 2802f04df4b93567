// The second pass of a logic recording's audit (over the samples the probe held, or the file
// read again): every UART channel a bus of its own, fed its characters with their own times,
// judged on t1.5/t3.5 at the sample clock's precision.
#pragma once

#include <memory>
#include <string>

#include "logic/plan/logic_plan.h"
#include "logic/tap/uart_tap.h"
#include "pipeline/pipeline.h"

namespace pvtap::analyzer {

// LogicRun: what reading the recording gave the pipeline.
struct LogicRun {
  std::string error;    // reading failed part way (what came before was fed)
  double end_time = 0;  // seconds from the recording's start
  InputReport input;
  std::vector<TappedLine> lines;  // per channel, in plan order, with the bus each feeds
};

// A bus per planned bus (named after its channels) in `pipeline`, and the tap that feeds them
// the characters, line errors and driver glitches of the samples it is given.
std::unique_ptr<UartTap> tap_planned_channels(const LogicPlan& plan, Pipeline& pipeline);

// The input line of the report: "sigrok logic, N UART channels at R MS/s".
std::string logic_link_text(const LogicPlan& plan);

// Feeds `pipeline` a bus per planned channel (named after the channel) and reads the
// recording into them; finishes the pipeline.
LogicRun run_logic_audit(const LogicPlan& plan, Pipeline& pipeline);

// The report's buses get their serial lines, and the report its rate (the first bus's).
void add_serial_lines(const LogicRun& run, AuditReport& report);

}  // namespace pvtap::analyzer
