// RunOutput: where one run's events and its report go: the chosen format on stdout and the
// --write pcap. Both commands open it before reading and close it after the report.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "events/event_fanout.h"
#include "events/event_writer.h"
#include "formatting/output_stream.h"
#include "mqtt/mqtt_options.h"
#include "mqtt/mqtt_publisher.h"
#include "report/audit_report.h"
#include "run/file_outputs.h"
#include "writers/event_writers.h"
#include "writers/pdu_capture_output.h"

namespace pvtap::analyzer {

// OutputSettings: what a run writes.
struct OutputSettings {
  OutputFormat format = OutputFormat::Text;
  bool summary_only = false;  // no per-event lines, only the report
  std::string write_path;     // --write; empty for none
  RunFacts written_run;       // the settings --write records carry (the bus is each event's)
  bool flush_each_record = false;
  FileOutputSettings files;  // --values, --html
  MqttOptions mqtt;          // --mqtt
  bool live = false;         // a live capture (the broker learns when pvtap goes away)
};

class RunOutput {
 public:
  RunOutput(const OutputSettings& settings, OutputStream& out);

  // Opens the --write file and begins the event output; false (after saying why on stderr)
  // when the file cannot be written.
  bool open();
  // Where the pipeline sends its events.
  EventWriter& events() { return fanout_; }
  // The report in the chosen format (csv: only with --summary-only, a CSV holds rows).
  void write_summary(const AuditReport& report);
  // Live capture: what is buffered for stdout and --values goes out now.
  void flush();
  // The capture clock reads `now`: what the broker gets per interval goes out when due.
  void tick(double now);
  // A serial tap's driver counters, for the broker's health of its bus.
  // When the broker is next due its per-interval messages; nullopt without --mqtt.
  std::optional<double> next_due() const { return mqtt_ ? mqtt_->next_due() : std::nullopt; }
  bool wants_line_errors() const { return mqtt_ != nullptr; }
  void line_errors(std::string_view bus, const std::optional<LineErrorCounts>& counts);
  // A live run's clock read `time` last and judged the waiting requests by it: the --write
  // file says so, for an audit of it to judge them alike.
  void clock_ended(double time);
  // The input ended at `time`: the broker gets everything held.
  void end_of_input(double time);
  bool stdout_pending() const { return !out_.buffer().empty(); }
  // Writes the HTML report and closes the files; false (after saying why) when writing one
  // of them failed.
  bool close(const AuditReport& report);
  std::uint64_t written_records() const { return pcap_ ? pcap_->records() : 0; }

 private:
  OutputSettings settings_;
  OutputStream& out_;
  std::unique_ptr<EventWriter> format_;
  std::optional<PduCaptureOutput> pcap_;
  FileOutputs files_;
  std::unique_ptr<MqttPublisher> mqtt_;
  EventFanout fanout_;
};

}  // namespace pvtap::analyzer
