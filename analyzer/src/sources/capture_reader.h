// CaptureReader: capture files (pcap, pcapng) and plain dumps of bus bytes fed into a
// pipeline record by record, in the order given, as one capture.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "console/progress_bar.h"
#include "pipeline/pipeline.h"
#include "report/audit_report.h"

namespace pvtap::analyzer {

// A one-line reason why an input cannot be audited (missing, not a capture, unsupported link
// type), checked for all inputs before any output is written; nullopt when all are fine.
std::optional<std::string> check_inputs(const std::vector<std::string>& captures,
                                        const std::vector<std::string>& raw_dumps);

class CaptureReader {
 public:
  // `read_ahead`: capture files are read on a second thread (ReadAheadCapture).
  CaptureReader(Pipeline& pipeline, ProgressBar& progress, bool read_ahead = false);

  // Reads every input; false when one ended early (truncated): what came before is fed.
  bool read(const std::vector<std::string>& captures, const std::vector<std::string>& raw_dumps);
  // The one-line stderr message for the input that ended early.
  void report_truncation() const;

  const std::vector<InputReport>& inputs() const { return inputs_; }
  double last_time() const { return last_time_; }  // of the latest record read

 private:
  bool read_capture(const std::string& path, std::uint64_t done_before);
  bool read_raw(const std::string& path, std::uint64_t done_before);

  Pipeline& pipeline_;
  ProgressBar& progress_;
  bool read_ahead_;
  std::vector<InputReport> inputs_;
  double last_time_ = 0;
};

// The total size of the files, for the progress bar.
std::uint64_t total_size(const std::vector<std::string>& captures,
                         const std::vector<std::string>& raw_dumps);

}  // namespace pvtap::analyzer
