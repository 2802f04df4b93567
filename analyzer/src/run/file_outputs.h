// FileOutputs: the outputs an audit writes to files of their own besides stdout: the register
// values (--values) and the HTML report (--html), which needs the whole run's timeline.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include <vector>

#include "events/event_fanout.h"
#include "events/event_writer.h"
#include "report/audit_report.h"
#include "writers/output_file.h"
#include "writers/values_writer.h"

namespace pvtap::analyzer {

class TimelineCollector;

// FileOutputSettings: which of those files to write.
struct FileOutputSettings {
  std::string values_path;  // --values; empty for none
  ValuesFormat values_format = ValuesFormat::Csv;
  std::string html_path;               // --html; empty for none
  std::vector<std::string> plot_keys;  // --plot
};

class FileOutputs {
 public:
  explicit FileOutputs(const FileOutputSettings& settings);
  ~FileOutputs();

  // Opens the files asked for; nullopt when all opened, else "PATH: reason".
  std::optional<std::string> open();
  // Adds the writers of the files asked for to the run's fan-out.
  void add_to(EventFanout& fanout);
  // Hands what --values has buffered to the file (live capture: rows as they happen).
  void flush();
  // Writes the HTML report and closes the files; nullopt when all went well.
  std::optional<std::string> finish(const AuditReport& report);

 private:
  FileOutputSettings settings_;
  OutputFile values_file_;
  OutputFile html_file_;  // opened at the start, so that a bad path fails before reading
  std::unique_ptr<EventWriter> values_;
  std::unique_ptr<TimelineCollector> timeline_;
};

}  // namespace pvtap::analyzer
