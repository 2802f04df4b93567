#include "cli/audit_input.h"

#include <sched.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <string>

#include "cli/sample_rate_argument.h"
#include "pvtap/pcap/link_types.h"

namespace pvtap::analyzer {
namespace {

// The CPUs this process may run on (taskset narrows them), at least 1.
unsigned available_cpus() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (::sched_getaffinity(0, sizeof set, &set) != 0) return 1;
  return static_cast<unsigned>(std::max(1, CPU_COUNT(&set)));
}

// False, with a line each, when the captures cannot be audited: they repeat each other's
// records, or none of them can be read (where some can, the others are named at the end).
bool captures_fit(const AuditOptions& options, const CapturePlan& plan) {
  if (plan.refusal) {
    std::fprintf(stderr, "pvtap: %s\n", plan.refusal->c_str());
    return false;
  }
  if (options.captures.empty() || !plan.readable.empty()) return true;
  for (const PlannedCapture& planned : plan.unreadable) {
    std::fprintf(stderr, "pvtap: %s: %s\n", planned.path.c_str(), planned.error.c_str());
  }
  return false;
}

}  // namespace

unsigned default_threads() {
  return available_cpus() > 1 ? 2 : 1;
}

void add_reading_options(CLI::App& command, AuditOptions& o) {
  command
      .add_option("--port", o.ports,
                  "gateway TCP/UDP port(s), comma-separated or repeated; other traffic is "
                  "ignored. Default: recognize the protocol on any port")
      ->check(CLI::Range(1, 65535).description(""))
      ->type_name("PORT")
      ->delimiter(',')
      ->allow_extra_args(false);
  command
      .add_option("--channels", o.logic_channels,
                  "logic recordings: a bus to decode, on one channel or on two (the requests' "
                  "and the replies', comma-separated); repeatable. Default: every channel "
                  "with UART traffic")
      ->type_name("NAME[,NAME]")
      ->allow_extra_args(false);
  command
      .add_option("--de", o.logic_drivers,
                  "logic recordings: a driver-enable channel (repeatable); the report gives "
                  "how long after each frame's last stop bit the driver was released")
      ->type_name("NAME")
      ->allow_extra_args(false);
  command
      .add_option("--samplerate", o.logic_sample_rate,
                  "logic recordings: samples per second (4000000, 4M, 500k), for a file that "
                  "does not give it (a CSV export) or in place of the one it gives")
      ->type_name("RATE");
  command.add_flag("--duplex", o.duplex,
                   "a 4-wire (RS422) tap: the two serial capture FILEs are one bus, the first "
                   "holding the requests' pair and the second the replies' pair, merged by their "
                   "timestamps");
  command
      .add_option("--threads", o.threads,
                  "1: read and analyse on one thread; 2: read capture files ahead on a second "
                  "thread (output is the same). Default: 2 when more than one CPU is available")
      ->type_name("N")
      ->check(CLI::Range(1, 2));
}

AuditInput::AuditInput(const AuditOptions& options) : options_(options) {}

AuditInput::~AuditInput() = default;

// Checks a logic recording's audit can run: it comes alone, and --channels comes with it.
bool AuditInput::logic_inputs_fit() const {
  const char* why = nullptr;
  if (logic_ && (options_.captures.size() != 1 || !options_.raw_dumps.empty())) {
    why = "a logic recording is audited alone (one FILE, no --raw)";
  } else if (logic_ && options_.duplex) {
    why = "--duplex reads two serial captures; a logic recording names its pairs with --channels";
  } else if (!logic_ && (!options_.logic_channels.empty() || !options_.logic_drivers.empty() ||
                         !options_.logic_sample_rate.empty())) {
    why = "--channels, --de and --samplerate describe a logic recording (.sr, .vcd, .csv)";
  }
  if (why != nullptr) std::fprintf(stderr, "pvtap: %s\n", why);
  return why == nullptr;
}

bool AuditInput::plan() {
  if (options_.captures.empty() && options_.raw_dumps.empty()) {
    std::fprintf(stderr, "pvtap: audit needs a capture FILE or --raw FILE (see --help)\n");
    return false;
  }
  if (!options_.captures.empty() && !options_.raw_dumps.empty()) {
    std::fprintf(stderr, "pvtap: give either capture FILEs or --raw dumps, not both\n");
    return false;
  }
  logic_ = std::any_of(options_.captures.begin(), options_.captures.end(),
                       [](const std::string& path) { return is_logic_recording(path); });
  if (!logic_inputs_fit()) return false;
  if (logic_) {
    double rate = 0;
    if (!read_sample_rate_option(options_.logic_sample_rate, rate)) return false;
    logic_plan_ = plan_logic_audit(options_.captures.front(), options_.logic_channels,
                                   options_.logic_drivers, rate);
    if (!logic_plan_->error.empty()) {
      std::fprintf(stderr, "pvtap: %s\n", logic_plan_->error.c_str());
      return false;
    }
    return true;
  }
  if (const auto error = check_raw_dumps(options_.raw_dumps)) {
    std::fprintf(stderr, "pvtap: %s\n", error->c_str());
    return false;
  }
  capture_plan_ = plan_captures(options_.captures, options_.duplex);
  return captures_fit(options_, capture_plan_) && duplex_fits();
}

// --duplex: two captures of serial records, one per pair. One that cannot be read is named at
// the end and the other is read all the same, as for any input.
bool AuditInput::duplex_fits() const {
  if (!options_.duplex) return true;
  const char* why = nullptr;
  if (options_.captures.size() != 2 || !options_.raw_dumps.empty()) {
    why = "--duplex reads two serial capture FILEs: the requests' pair, then the replies' pair";
  }
  for (const PlannedCapture& planned : capture_plan_.readable) {
    const auto kind = input_kind_of(planned.link_type);
    if (why == nullptr && kind != InputKind::Serial && kind != InputKind::RtacSerial) {
      std::fprintf(stderr,
                   "pvtap: --duplex reads serial captures (USER0-USER15, RTAC serial); %s has "
                   "records of another link type\n",
                   planned.path.c_str());
      return false;
    }
  }
  if (why != nullptr) std::fprintf(stderr, "pvtap: %s\n", why);
  return why == nullptr;
}

PipelineSettings AuditInput::pipeline_settings(PipelineSettings settings) const {
  if (!logic_) settings.has_timestamps = options_.raw_dumps.empty();
  if (logic_) settings.from_recording_start = true;
  return settings;
}

bool AuditInput::read(Pipeline& pipeline) {
  if (logic_) {
    logic_run_ = run_logic_audit(*logic_plan_, pipeline);
    end_time_ = logic_run_->end_time;
    return logic_run_->error.empty();
  }
  progress_ = std::make_unique<ProgressBar>(options_.progress,
                                            total_size(options_.captures, options_.raw_dumps));
  reader_ = std::make_unique<CaptureReader>(pipeline, *progress_, options_.threads > 1);
  const bool complete = reader_->read(capture_plan_, options_.raw_dumps);
  end_time_ = reader_->last_time();
  pipeline.finish(end_time_);
  progress_->clear();
  return complete;
}

void AuditInput::complete(AuditReport& report) const {
  if (logic_run_) add_serial_lines(*logic_run_, report);
  if (reader_) report.inputs = reader_->inputs();
}

void AuditInput::report_problems() const {
  if (logic_run_ && !logic_run_->error.empty()) {
    std::fprintf(stderr, "pvtap: %s: %s\n", logic_plan_->path.c_str(), logic_run_->error.c_str());
  }
  if (reader_) reader_->report_problems();
}

}  // namespace pvtap::analyzer
