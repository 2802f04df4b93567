// FileOutputs: the outputs an audit writes to files of their own besides stdout: the register
// values (--values) and the HTML report (--html), which needs the whole run's timeline.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "audit_options.h"
#include "audit_report.h"
#include "event_writer.h"
#include "output_file.h"

namespace pvtap::analyzer {

class TimelineCollector;

class FileOutputs {
 public:
  explicit FileOutputs(const AuditOptions& options);
  ~FileOutputs();

  // Opens the files asked for; nullopt when all opened, else "PATH: reason".
  std::optional<std::string> open();
  // The writer the bus sessions' events go to: `format` (stdout, may be null) alone when no
  // file output was asked for, so that the plain run is unchanged; else a fan-out to all.
  std::unique_ptr<EventWriter> events_for(std::unique_ptr<EventWriter> format);
  // Hands what --values has buffered to the file (live capture: rows as they happen).
  void flush();
  // Writes the HTML report and closes the files; nullopt when all went well.
  std::optional<std::string> finish(const AuditReport& report);

 private:
  const AuditOptions& options_;
  OutputFile values_file_;
  OutputFile html_file_;  // opened at the start, so that a bad path fails before reading
  std::unique_ptr<EventWriter> values_;
  std::unique_ptr<TimelineCollector> timeline_;
  std::unique_ptr<EventWriter> format_;
};

}  // namespace pvtap::analyzer
