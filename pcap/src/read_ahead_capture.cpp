#include "pvtap/pcap/read_ahead_capture.h"

namespace pvtap {

bool ReadAheadCapture::open(const std::string& path) {
  if (!file_.open(path)) {
    error_ = file_.error();
    return false;
  }
  if (read_ahead_) ahead_.start(file_, kBatches, kBatchBytes);
  return true;
}

CaptureFile::Next ReadAheadCapture::next(CapturedPacket& packet) {
  if (!read_ahead_) return file_.next(packet);
  while (!current_ || !current_->next(packet)) {
    if (current_ && current_->after() != CaptureFile::Next::Packet) {
      error_ = current_->error();
      return current_->after();
    }
    current_ = ahead_.exchange(std::move(current_));
    position_ = current_->position();
  }
  ++packets_;
  return CaptureFile::Next::Packet;
}

}  // namespace pvtap
