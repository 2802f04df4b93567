// FileOutputs: --values rows as the events come, --html at the end from the report model.
#include "file_outputs.h"

#include <vector>

#include "event_fan_out.h"
#include "html_report.h"
#include "timeline_collector.h"
#include "values_writer.h"

namespace pvtap::analyzer {

FileOutputs::FileOutputs(const AuditOptions& options) : options_(options) {}

FileOutputs::~FileOutputs() = default;

std::optional<std::string> FileOutputs::open() {
  if (!options_.values_path.empty()) {
    if (auto error = values_file_.open(options_.values_path)) return error;
    values_ = make_values_writer(options_.values_format, values_file_.stream());
  }
  if (!options_.html_path.empty()) {
    if (auto error = html_file_.open(options_.html_path)) return error;
    timeline_ = std::make_unique<TimelineCollector>();
  }
  return std::nullopt;
}

std::unique_ptr<EventWriter> FileOutputs::events_for(std::unique_ptr<EventWriter> format) {
  if (!values_ && !timeline_) return format;
  format_ = std::move(format);
  std::vector<EventWriter*> writers;
  for (EventWriter* w : {format_.get(), values_.get(), static_cast<EventWriter*>(timeline_.get())})
    if (w != nullptr) writers.push_back(w);
  return std::make_unique<EventFanOut>(std::move(writers));
}

void FileOutputs::flush() {
  if (values_) values_file_.flush();
}

std::optional<std::string> FileOutputs::finish(const AuditReport& report) {
  std::optional<std::string> error = values_file_.close();
  if (timeline_) {
    write_html_report(report, timeline_->finish(), HtmlOptions{options_.plot_keys},
                      html_file_.stream());
    if (auto failed = html_file_.close()) return failed;
  }
  return error;
}

}  // namespace pvtap::analyzer
