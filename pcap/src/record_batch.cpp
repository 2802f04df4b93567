#include "pvtap/pcap/record_batch.h"

#include <cstring>

namespace pvtap {

RecordBatch::RecordBatch(std::size_t capacity)
    : bytes_(std::make_unique_for_overwrite<std::uint8_t[]>(capacity)), capacity_(capacity) {}

CaptureFile::Next RecordBatch::fill(CaptureFile& file, std::size_t bytes) {
  used_ = 0;
  records_.clear();
  next_ = 0;
  CapturedPacket packet;
  for (;;) {
    const CaptureFile::Next next = file.next(packet);
    if (next != CaptureFile::Next::Packet) {
      after_ = next;
      error_ = file.error();
      break;
    }
    records_.push_back(Record{packet.time, static_cast<std::uint32_t>(used_),
                              static_cast<std::uint32_t>(packet.bytes.size()),
                              packet.length_on_wire});
    append(packet.bytes);
    if (used_ >= bytes) break;
  }
  position_ = file.position();
  return after_;
}

void RecordBatch::append(std::span<const std::uint8_t> bytes) {
  if (used_ + bytes.size() > capacity_) {
    const std::size_t capacity = used_ + bytes.size();
    auto grown = std::make_unique_for_overwrite<std::uint8_t[]>(capacity);
    if (used_ > 0) std::memcpy(grown.get(), bytes_.get(), used_);
    bytes_ = std::move(grown);
    capacity_ = capacity;
  }
  if (!bytes.empty()) std::memcpy(bytes_.get() + used_, bytes.data(), bytes.size());
  used_ += bytes.size();
}

}  // namespace pvtap
