#include "pvtap/pcap/read_ahead_thread.h"

namespace pvtap {

ReadAheadThread::~ReadAheadThread() {
  {
    const std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  changed_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void ReadAheadThread::start(CaptureFile& file, std::size_t batches, std::size_t batch_bytes) {
  for (std::size_t i = 0; i < batches; ++i) {
    // Room for the record that crosses batch_bytes, at the usual sizes: a batch's buffer is
    // then allocated once.
    free_.push_back(std::make_unique<RecordBatch>(batch_bytes + batch_bytes / 8));
  }
  thread_ = std::thread([this, &file, batch_bytes] { read_batches(file, batch_bytes); });
}

void ReadAheadThread::read_batches(CaptureFile& file, std::size_t batch_bytes) {
  for (;;) {
    std::unique_ptr<RecordBatch> batch = take_free_batch();
    if (!batch) return;
    const CaptureFile::Next after = batch->fill(file, batch_bytes);
    {
      const std::lock_guard lock(mutex_);
      full_.push_back(std::move(batch));
    }
    changed_.notify_all();
    if (after != CaptureFile::Next::Packet) return;
  }
}

std::unique_ptr<RecordBatch> ReadAheadThread::take_free_batch() {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [this] { return stopping_ || !free_.empty(); });
  if (stopping_) return nullptr;
  std::unique_ptr<RecordBatch> batch = std::move(free_.back());
  free_.pop_back();
  return batch;
}

std::unique_ptr<RecordBatch> ReadAheadThread::exchange(std::unique_ptr<RecordBatch> done) {
  std::unique_lock lock(mutex_);
  if (done) {
    free_.push_back(std::move(done));
    changed_.notify_all();
  }
  changed_.wait(lock, [this] { return !full_.empty(); });
  std::unique_ptr<RecordBatch> batch = std::move(full_.front());
  full_.pop_front();
  return batch;
}

}  // namespace pvtap
