// FileOutputs: --values rows as the events come, --html at the end from the report model.
#include "run/file_outputs.h"

#include "html/html_report.h"
#include "html/timeline_collector.h"

namespace pvtap::analyzer {

FileOutputs::FileOutputs(const FileOutputSettings& settings) : settings_(settings) {}

FileOutputs::~FileOutputs() = default;

std::optional<std::string> FileOutputs::open() {
  if (!settings_.values_path.empty()) {
    if (auto error = values_file_.open(settings_.values_path)) return error;
    values_ = make_values_writer(settings_.values_format, values_file_.stream());
  }
  if (!settings_.html_path.empty()) {
    if (auto error = html_file_.open(settings_.html_path)) return error;
    timeline_ = std::make_unique<TimelineCollector>();
  }
  return std::nullopt;
}

void FileOutputs::add_to(EventFanout& fanout) {
  if (values_) fanout.add(*values_);
  if (timeline_) fanout.add(*timeline_);
}

void FileOutputs::flush() {
  if (values_) values_file_.flush();
}

std::optional<std::string> FileOutputs::finish(const AuditReport& report) {
  std::optional<std::string> error = values_file_.close();
  if (timeline_) {
    write_html_report(report, timeline_->finish(), HtmlOptions{settings_.plot_keys},
                      html_file_.stream());
    if (auto failed = html_file_.close()) return failed;
  }
  return error;
}

}  // namespace pvtap::analyzer
