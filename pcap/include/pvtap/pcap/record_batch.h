// RecordBatch: consecutive records of a capture in one buffer, and how the file went on after.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "pvtap/pcap/capture_file.h"

namespace pvtap {

// Filled on the reading thread and handed to the caller's whole, so that neither waits for
// the other record by record.
class RecordBatch {
 public:
  // Room for `capacity` bytes of records, allocated once at the usual record sizes.
  explicit RecordBatch(std::size_t capacity);

  // Reads records until they hold at least `bytes` (the record that reaches it included) or
  // the file ends; End or Truncated when it did.
  CaptureFile::Next fill(CaptureFile& file, std::size_t bytes);
  // The next record not handed out since fill(); false when none is left. `bytes` stays
  // valid until the batch is filled again.
  // Inline: called once per record on the audit's hot path.
  bool next(CapturedPacket& packet) {
    if (next_ == records_.size()) return false;
    const Record& record = records_[next_++];
    packet.time = record.time;
    packet.bytes = std::span<const std::uint8_t>(bytes_.get() + record.offset, record.size);
    packet.length_on_wire = record.length_on_wire;
    return true;
  }

  std::uint64_t position() const { return position_; }  // the file's, after the last record
  CaptureFile::Next after() const { return after_; }    // End or Truncated: the last batch
  const std::string& error() const { return error_; }

 private:
  struct Record {
    double time;
    std::uint32_t offset;
    std::uint32_t size;
    std::uint32_t length_on_wire;
  };

  void append(std::span<const std::uint8_t> bytes);

  // Records' bytes, back to back; a plain buffer, since a vector's resize would zero what
  // the copy overwrites at once. `capacity_` grows only for a record larger than a batch.
  std::unique_ptr<std::uint8_t[]> bytes_;
  std::size_t capacity_;
  std::size_t used_ = 0;
  std::vector<Record> records_;
  std::size_t next_ = 0;
  std::uint64_t position_ = 0;
  CaptureFile::Next after_ = CaptureFile::Next::Packet;
  std::string error_;
};

}  // namespace pvtap
