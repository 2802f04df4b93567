// CaptureReader: capture files (pcap, pcapng) fed into a pipeline as one capture, record by
// record in the order of their times (files that overlap are merged), then plain dumps of bus
// bytes in the order given. A damaged file is reported and the others are read all the same.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "console/progress_bar.h"
#include "pipeline/pipeline.h"
#include "report/audit_report.h"
#include "sources/capture_order.h"

namespace pvtap::analyzer {

// A one-line reason why a plain dump (--raw) cannot be read; nullopt when all can.
std::optional<std::string> check_raw_dumps(const std::vector<std::string>& raw_dumps);

class CaptureReader {
 public:
  // `read_ahead`: capture files are read on a second thread (ReadAheadCapture).
  CaptureReader(Pipeline& pipeline, ProgressBar& progress, bool read_ahead = false);
  ~CaptureReader();
  CaptureReader(const CaptureReader&) = delete;
  CaptureReader& operator=(const CaptureReader&) = delete;

  // Reads every input; false when one was damaged, not read, or repeated another's records
  // (report_problems() says which): everything read before and beside it is fed.
  bool read(const CapturePlan& plan, const std::vector<std::string>& raw_dumps);
  // One stderr line per input that was damaged or not read, and one for repeated records.
  void report_problems() const;

  // In the order read; the files that could not be read last.
  const std::vector<InputReport>& inputs() const { return inputs_; }
  double last_time() const { return last_time_; }  // of the latest record read

 private:
  struct Source;
  bool read_captures(const CapturePlan& plan);
  void open_due(const CapturePlan& plan, std::size_t& next,
                std::vector<std::unique_ptr<Source>>& active);
  void open(const PlannedCapture& planned, std::vector<std::unique_ptr<Source>>& active);
  bool feed_until(Source& source, double until, const std::vector<std::unique_ptr<Source>>& active);
  static double first_time_of(const CapturePlan& plan, std::size_t next);
  bool advance(Source& source);
  bool ended(Source& source, CaptureFile::Next next);
  double step_back(Source& source, double time);
  void close(Source& source);
  std::optional<std::string> repeat_of(const Source& source,
                                       const std::vector<std::unique_ptr<Source>>& active) const;
  bool read_raw(const std::string& path);

  Pipeline& pipeline_;
  ProgressBar& progress_;
  bool read_ahead_;
  std::vector<InputReport> inputs_;
  std::optional<std::string> repeat_;
  double last_time_ = 0;
  std::uint64_t done_bytes_ = 0;  // of the files read to their end, for the progress bar
  std::uint64_t fed_ = 0;         // records fed, to look at the progress now and then
};

// The total size of the files, for the progress bar.
std::uint64_t total_size(const std::vector<std::string>& captures,
                         const std::vector<std::string>& raw_dumps);

}  // namespace pvtap::analyzer
