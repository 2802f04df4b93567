#include "pvtap/capture/read_ahead_capture.h"

#include <cstring>

namespace pvtap {

ReadAheadCapture::~ReadAheadCapture() {
  {
    const std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  changed_.notify_all();
  if (reader_.joinable()) reader_.join();
}

bool ReadAheadCapture::open(const std::string& path) {
  if (!file_.open(path)) {
    error_ = file_.error();
    return false;
  }
  if (!read_ahead_) return true;
  for (std::size_t i = 0; i < kBatches; ++i) {
    auto batch = std::make_unique<Batch>();
    // Room for the record that crosses kBatchBytes, at the usual sizes: a batch's buffer is
    // then allocated once.
    batch->capacity = kBatchBytes + kBatchBytes / 8;
    batch->bytes = std::make_unique_for_overwrite<std::uint8_t[]>(batch->capacity);
    free_.push_back(std::move(batch));
  }
  reader_ = std::thread([this] { read_batches(); });
  return true;
}

void ReadAheadCapture::read_batches() {
  for (;;) {
    std::unique_ptr<Batch> batch = take_free_batch();
    if (!batch) return;
    const CaptureFile::Next after = fill(*batch);
    {
      const std::lock_guard lock(mutex_);
      full_.push_back(std::move(batch));
    }
    changed_.notify_all();
    if (after != CaptureFile::Next::Packet) return;
  }
}

// Only the reading thread touches file_ while it runs; a batch is handed over whole.
CaptureFile::Next ReadAheadCapture::fill(Batch& batch) {
  batch.used = 0;
  batch.slots.clear();
  CapturedPacket packet;
  for (;;) {
    const CaptureFile::Next next = file_.next(packet);
    if (next != CaptureFile::Next::Packet) {
      batch.after = next;
      batch.error = file_.error();
      break;
    }
    batch.slots.push_back(Slot{packet.time, static_cast<std::uint32_t>(batch.used),
                               static_cast<std::uint32_t>(packet.bytes.size()),
                               packet.length_on_wire});
    append(batch, packet.bytes);
    if (batch.used >= kBatchBytes) break;
  }
  batch.position = file_.position();
  return batch.after;
}

void ReadAheadCapture::append(Batch& batch, std::span<const std::uint8_t> bytes) {
  if (batch.used + bytes.size() > batch.capacity) {
    const std::size_t capacity = batch.used + bytes.size();
    auto grown = std::make_unique_for_overwrite<std::uint8_t[]>(capacity);
    if (batch.used > 0) std::memcpy(grown.get(), batch.bytes.get(), batch.used);
    batch.bytes = std::move(grown);
    batch.capacity = capacity;
  }
  if (!bytes.empty()) std::memcpy(batch.bytes.get() + batch.used, bytes.data(), bytes.size());
  batch.used += bytes.size();
}

std::unique_ptr<ReadAheadCapture::Batch> ReadAheadCapture::take_free_batch() {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [this] { return stopping_ || !free_.empty(); });
  if (stopping_) return nullptr;
  std::unique_ptr<Batch> batch = std::move(free_.back());
  free_.pop_back();
  return batch;
}

void ReadAheadCapture::take_full_batch() {
  std::unique_lock lock(mutex_);
  if (current_) {
    free_.push_back(std::move(current_));
    changed_.notify_all();
  }
  changed_.wait(lock, [this] { return !full_.empty(); });
  current_ = std::move(full_.front());
  full_.pop_front();
  next_slot_ = 0;
}

CaptureFile::Next ReadAheadCapture::next(CapturedPacket& packet) {
  if (!read_ahead_) return file_.next(packet);
  while (!current_ || next_slot_ == current_->slots.size()) {
    if (current_ && current_->after != CaptureFile::Next::Packet) {
      error_ = current_->error;
      return current_->after;
    }
    take_full_batch();
    position_ = current_->position;
  }
  const Slot& slot = current_->slots[next_slot_++];
  packet.time = slot.time;
  packet.bytes = std::span<const std::uint8_t>(current_->bytes.get() + slot.offset, slot.size);
  packet.length_on_wire = slot.length_on_wire;
  ++packets_;
  return CaptureFile::Next::Packet;
}

}  // namespace pvtap
