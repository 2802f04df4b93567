// AuditInput: the inputs of one audit (capture files, plain dumps given with --raw, or one
// logic recording) checked, planned and read into a pipeline. `pvtap audit` reads its inputs
// through it, and `pvtap diff` each of its two sides, so both read bytes the same way.
#pragma once

#include <memory>
#include <optional>

#include "cli/command_options.h"
#include "console/progress_bar.h"
#include "logic/logic_run.h"
#include "logic/plan/logic_plan.h"
#include "pipeline/pipeline.h"
#include "report/audit_report.h"
#include "sources/capture_order.h"
#include "sources/capture_reader.h"

namespace CLI {
class App;
}

namespace pvtap::analyzer {

// The options that change how the inputs are read, beyond the protocol's: --port, --channels,
// --de, --samplerate, --threads.
void add_reading_options(CLI::App& command, AuditOptions& o);
// --threads when not given: 2 where this process may run on more than one CPU, else 1.
unsigned default_threads();

class AuditInput {
 public:
  // `options` must outlive it.
  explicit AuditInput(const AuditOptions& options);
  ~AuditInput();
  AuditInput(const AuditInput&) = delete;
  AuditInput& operator=(const AuditInput&) = delete;

  // Whether the inputs go together (FILEs or --raw, a logic recording alone) and can be
  // planned; false after a `pvtap:` line on stderr for each reason.
  bool plan();
  // The settings the pipeline reading these inputs needs (plain dumps have no time).
  PipelineSettings pipeline_settings(PipelineSettings settings) const;
  // Reads every input into `pipeline` and finishes it. False when an input was damaged, not
  // read or repeated another's records: what could be read was fed all the same
  // (report_problems() says what went wrong).
  bool read(Pipeline& pipeline);
  // The time the input ended (the latest record's).
  double end_time() const { return end_time_; }
  // The report's inputs, and a logic recording's serial lines.
  void complete(AuditReport& report) const;
  // One `pvtap:` line on stderr per problem read() found.
  void report_problems() const;

 private:
  bool logic_inputs_fit() const;
  bool duplex_fits() const;

  const AuditOptions& options_;
  bool logic_ = false;
  std::optional<LogicPlan> logic_plan_;
  std::optional<LogicRun> logic_run_;
  CapturePlan capture_plan_;
  std::unique_ptr<ProgressBar> progress_;
  std::unique_ptr<CaptureReader> reader_;
  double end_time_ = 0;
};

}  // namespace pvtap::analyzer
