#include "run/run_output.h"

#include <cstdio>

#include "report/report_writers.h"

namespace pvtap::analyzer {
namespace {

std::unique_ptr<EventWriter> make_event_writer(OutputFormat format, OutputStream& out) {
  switch (format) {
    case OutputFormat::Jsonl:
      return make_jsonl_event_writer(out);
    case OutputFormat::Csv:
      return make_csv_event_writer(out);
    case OutputFormat::Text:
      break;
  }
  return make_text_event_writer(out);
}

}  // namespace

RunOutput::RunOutput(const OutputSettings& settings, OutputStream& out)
    : settings_(settings), out_(out), files_(settings.files) {}

bool RunOutput::open() {
  if (!settings_.write_path.empty()) {
    pcap_.emplace();
    if (!pcap_->open(settings_.write_path, settings_.flush_each_record, settings_.written_run)) {
      std::fprintf(stderr, "pvtap: cannot write %s: %s\n", settings_.write_path.c_str(),
                   pcap_->error().c_str());
      return false;
    }
    fanout_.add(*pcap_);
  }
  // Before any output line (a csv header): a broker that refuses is an error with no output.
  if (settings_.mqtt.active()) {
    std::string error;
    mqtt_ = MqttPublisher::open(settings_.mqtt, settings_.live, error);
    if (!mqtt_) {
      std::fprintf(stderr, "pvtap: %s\n", error.c_str());
      return false;
    }
  }
  if (const auto error = files_.open()) {
    std::fprintf(stderr, "pvtap: cannot write %s\n", error->c_str());
    return false;
  }
  if (!settings_.summary_only) {
    format_ = make_event_writer(settings_.format, out_);
    fanout_.add(*format_);
  }
  files_.add_to(fanout_);
  if (mqtt_) fanout_.add(*mqtt_);
  fanout_.begin();
  return true;
}

void RunOutput::write_summary(const AuditReport& report) {
  switch (settings_.format) {
    case OutputFormat::Jsonl:
      write_json_summary(report, out_);
      return;
    case OutputFormat::Csv:
      if (settings_.summary_only) write_text_report(report, out_);
      return;
    case OutputFormat::Text:
      write_text_report(report, out_);
      return;
  }
}

void RunOutput::flush() {
  if (!out_.buffer().empty()) out_.flush();
  files_.flush();
}

void RunOutput::tick(double now) {
  if (mqtt_) mqtt_->tick(now);
}

void RunOutput::line_errors(std::string_view bus, const std::optional<LineErrorCounts>& counts) {
  if (mqtt_) mqtt_->line_errors(bus, counts);
}

void RunOutput::clock_ended(double time) {
  if (pcap_) pcap_->end_of_input(time);
}

void RunOutput::end_of_input(double time) {
  if (mqtt_) mqtt_->finish(time);
}

bool RunOutput::close(const AuditReport& report) {
  if (const auto error = files_.finish(report)) {
    std::fprintf(stderr, "pvtap: cannot write %s\n", error->c_str());
    return false;
  }
  if (pcap_ && !pcap_->close()) {
    std::fprintf(stderr, "pvtap: cannot write %s: %s\n", settings_.write_path.c_str(),
                 pcap_->error().c_str());
    return false;
  }
  return true;
}

}  // namespace pvtap::analyzer
