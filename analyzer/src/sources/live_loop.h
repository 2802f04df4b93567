// LiveLoop: what the two live sources of pvtap sniff (serial taps and a network interface)
// share: when to stop, the output as events happen, the status line, and how long to sleep.
#pragma once

#include <cstdint>
#include <string>
#include <utility>

#include "console/status_line.h"
#include "pipeline/pipeline.h"
#include "report/live_report.h"
#include "run/run_output.h"
#include "sources/live_options.h"

namespace pvtap::analyzer {

class LiveLoop {
 public:
  // The clock starts now.
  LiveLoop(const LiveOptions& options, Pipeline& pipeline, RunOutput& output);

  // A stop signal came, --count frames were seen or --duration has passed.
  bool should_stop() const;
  bool count_reached() const;
  // How long a source may sleep from `now`: until the first of the pipeline's next deadline,
  // the status line and the end of --duration.
  double wake_at(double now) const;
  // Events (and --values rows) go out as they happen; the status line is redrawn when due.
  void after_wake(double now);
  // The run's output, for what a source reports besides events (line error counters).
  RunOutput& output() { return output_; }
  // Shown at the head of the status line (a serial tap's rate search); empty for none.
  void set_status_note(std::string note) { status_note_ = std::move(note); }
  // A line is about to go to stderr: the status line makes room for it.
  void make_room_on_stderr() { status_.clear(); }
  // A record of this time was fed: the capture ends no earlier.
  void saw_time(double time);
  // The source's records are timed by a sample clock (a logic stream), not by the wall clock:
  // the capture ends at its last record, not at the wall clock's now.
  void use_sample_clock() { sample_clock_ = true; }
  // Ends the capture at `now`: how long it ran and whether a signal stopped it.
  void end(double now, LiveSources& live);
  double last_time() const { return last_time_; }

 private:
  void show_status(double now);

  const LiveOptions& options_;
  Pipeline& pipeline_;
  RunOutput& output_;
  StatusLine status_;
  double started_;
  double last_time_ = 0;
  std::string status_note_;
  bool sample_clock_ = false;
};

}  // namespace pvtap::analyzer
