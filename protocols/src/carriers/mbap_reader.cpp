#include "pvtap/carriers/mbap_reader.h"

#include "pvtap/carriers/mbap_structure.h"

namespace pvtap {

MbapTotals& MbapTotals::operator+=(const MbapTotals& o) {
  bytes_in += o.bytes_in;
  adus += o.adus;
  carrier_bytes += o.carrier_bytes;
  frame_bytes += o.frame_bytes;
  skipped_bytes += o.skipped_bytes;
  findings += o.findings;
  return *this;
}

MbapReader::MbapReader(MbapSink& sink) : sink_(sink) {}

void MbapReader::feed(std::span<const std::uint8_t> bytes, double time) {
  totals_.bytes_in += bytes.size();
  const std::size_t piece_start = buffer_.size();
  buffer_.insert(buffer_.end(), bytes.begin(), bytes.end());
  while (read_one(piece_start, time)) {
  }
  // Read bytes are dropped so that the buffer holds one unfinished ADU at most.
  buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(read_));
  base_ += read_;
  read_ = 0;
}

// Reads the ADU at read_, or gives up bytes for a header that lied; false when it must wait.
bool MbapReader::read_one(std::size_t piece_start, double time) {
  const std::span<const std::uint8_t> rest(buffer_.data() + read_, buffer_.size() - read_);
  const auto h = read_mbap_header(rest);
  if (!h) return false;
  if (!plausible_mbap_header(*h)) {
    const MbapProblem p = h->protocol_id != 0          ? MbapProblem::ProtocolId
                          : h->length < kMbapMinLength ? MbapProblem::LengthTooShort
                                                       : MbapProblem::LengthTooLong;
    give_up(buffer_.size(), p, time);
    return false;
  }
  const std::size_t size = kMbapCarrierBytes + h->length;
  const bool spans_pieces = read_ < piece_start && read_ + size > piece_start;
  if (spans_pieces || (read_ < piece_start && size > rest.size())) {
    const std::span<const std::uint8_t> piece(buffer_.data() + piece_start,
                                              buffer_.size() - piece_start);
    if (whole_mbap_adus(piece)) {
      give_up(piece_start, MbapProblem::LengthOverruns, time);
      return true;
    }
  }
  if (size > rest.size()) return false;
  sink_.on_adu(MbapAdu{base_ + read_, h->transaction, h->unit,
                       rest.subspan(kMbapCarrierBytes, h->length), time});
  ++totals_.adus;
  totals_.carrier_bytes += kMbapCarrierBytes;
  totals_.frame_bytes += h->length;
  read_ += size;
  return true;
}

void MbapReader::give_up(std::size_t to, MbapProblem problem, double time) {
  MbapFinding f;
  f.offset = base_ + read_;
  f.problem = problem;
  if (const auto h = read_mbap_header({buffer_.data() + read_, buffer_.size() - read_})) {
    f.protocol_id = h->protocol_id;
    f.declared_length = h->length;
  }
  f.skipped = to - read_;
  f.time = time;
  ++totals_.findings;
  totals_.skipped_bytes += f.skipped;
  read_ = to;
  sink_.on_finding(f);
}

void MbapReader::discontinuity(double time) {
  if (pending_bytes() > 0) give_up(buffer_.size(), MbapProblem::Truncated, time);
  buffer_.clear();
  base_ += read_;
  read_ = 0;
}

void MbapReader::finish(double time) {
  discontinuity(time);
}

}  // namespace pvtap
