// ReadAheadCapture: a capture file whose records are read on a second thread, a few batches
// ahead of the caller, so that libpcap's reading overlaps the analysis of earlier records.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "pvtap/pcap/capture_file.h"
#include "pvtap/pcap/read_ahead_thread.h"
#include "pvtap/pcap/record_batch.h"

namespace pvtap {

class ReadAheadCapture {
 public:
  // Records are copied into batches of about this many bytes (a batch ends with the record
  // that reaches it); at most kBatches exist, so memory is bounded whatever the capture's size.
  static constexpr std::size_t kBatchBytes = 1024 * 1024;
  static constexpr std::size_t kBatches = 4;

  // `read_ahead` false reads on the caller's thread, record by record, as CaptureFile does.
  explicit ReadAheadCapture(bool read_ahead) : read_ahead_(read_ahead) {}
  ReadAheadCapture(const ReadAheadCapture&) = delete;
  ReadAheadCapture& operator=(const ReadAheadCapture&) = delete;

  // Opens the capture and starts reading; false with error() set when it cannot be read.
  bool open(const std::string& path);

  // The next record, in file order; `bytes` stays valid until the next call.
  CaptureFile::Next next(CapturedPacket& packet);

  int link_type() const { return file_.link_type(); }
  std::string link_type_name() const { return file_.link_type_name(); }
  // Why open() failed or next() returned Truncated. The reading thread's own copy is not
  // looked at while it runs: the batch that ends the file carries its error.
  const std::string& error() const { return read_ahead_ ? error_ : file_.error(); }
  std::uint64_t packets() const { return read_ahead_ ? packets_ : file_.packets(); }
  std::uint64_t size() const { return file_.size(); }
  // Bytes of the file read up to the records handed out so far (at a batch's granularity).
  std::uint64_t position() const { return read_ahead_ ? position_ : file_.position(); }

 private:
  const bool read_ahead_;
  CaptureFile file_;
  ReadAheadThread ahead_;  // after file_: it stops reading before the file closes

  // The caller's side, touched by its thread only.
  std::unique_ptr<RecordBatch> current_;
  std::uint64_t packets_ = 0;
  std::uint64_t position_ = 0;
  std::string error_;
};

}  // namespace pvtap
