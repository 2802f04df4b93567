// ReadAheadCapture: a capture file whose records are read on a second thread, a few batches
// ahead of the caller, so that libpcap's reading overlaps the analysis of earlier records.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include "pvtap/capture/capture_file.h"

namespace pvtap {

class ReadAheadCapture {
 public:
  // Records are copied into batches of about this many bytes (a batch ends with the record
  // that reaches it); at most kBatches exist, so memory is bounded whatever the capture's size.
  static constexpr std::size_t kBatchBytes = 1024 * 1024;
  static constexpr std::size_t kBatches = 4;

  // `read_ahead` false reads on the caller's thread, record by record, as CaptureFile does.
  explicit ReadAheadCapture(bool read_ahead) : read_ahead_(read_ahead) {}
  ~ReadAheadCapture();
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
  struct Slot {
    double time;
    std::uint32_t offset;
    std::uint32_t size;
    std::uint32_t length_on_wire;
  };
  // Batch: consecutive records, and how the file went on after the last of them.
  struct Batch {
    // Records' bytes, back to back; a plain buffer, since a vector's resize would zero what
    // the copy overwrites at once. `capacity` grows only for a record larger than a batch.
    std::unique_ptr<std::uint8_t[]> bytes;
    std::size_t capacity = 0;
    std::size_t used = 0;
    std::vector<Slot> slots;
    std::uint64_t position = 0;
    CaptureFile::Next after = CaptureFile::Next::Packet;  // End or Truncated: the last batch
    std::string error;
  };

  void read_batches();                   // the reading thread
  CaptureFile::Next fill(Batch& batch);  // reads records until the batch is full
  static void append(Batch& batch, std::span<const std::uint8_t> bytes);
  std::unique_ptr<Batch> take_free_batch();  // nullptr once stopped
  void take_full_batch();                    // the caller's side: waits for the next batch

  const bool read_ahead_;
  CaptureFile file_;
  std::thread reader_;

  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<std::unique_ptr<Batch>> full_;
  std::vector<std::unique_ptr<Batch>> free_;
  bool stopping_ = false;

  // The caller's side, touched by its thread only.
  std::unique_ptr<Batch> current_;
  std::size_t next_slot_ = 0;
  std::uint64_t packets_ = 0;
  std::uint64_t position_ = 0;
  std::string error_;
};

}  // namespace pvtap
