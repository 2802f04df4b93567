// ReadAheadThread: fills batches of a capture's records on a thread of its own.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "pvtap/pcap/capture_file.h"
#include "pvtap/pcap/record_batch.h"

namespace pvtap {

// A fixed number of batches go round between the thread and the caller, so that the thread
// stays at most that many batches ahead and memory is bounded whatever the capture's size.
class ReadAheadThread {
 public:
  ReadAheadThread() = default;
  ~ReadAheadThread();  // stops the thread, even while it waits for a free batch
  ReadAheadThread(const ReadAheadThread&) = delete;
  ReadAheadThread& operator=(const ReadAheadThread&) = delete;

  // Starts reading `file` into `batches` batches of about `batch_bytes`; only the thread
  // touches the file from now on, until the batch that ends it.
  void start(CaptureFile& file, std::size_t batches, std::size_t batch_bytes);

  // Hands back a batch whose records were all taken (nullptr at first) and waits for the
  // next full one.
  std::unique_ptr<RecordBatch> exchange(std::unique_ptr<RecordBatch> done);

 private:
  void read_batches(CaptureFile& file, std::size_t batch_bytes);  // the thread
  std::unique_ptr<RecordBatch> take_free_batch();                 // nullptr once stopped

  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<std::unique_ptr<RecordBatch>> full_;
  std::vector<std::unique_ptr<RecordBatch>> free_;
  bool stopping_ = false;
  std::thread thread_;
};

}  // namespace pvtap
