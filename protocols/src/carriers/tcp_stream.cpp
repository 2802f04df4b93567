#include "pvtap/carriers/tcp_stream.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pvtap {
namespace {

// An acknowledgement this far beyond the stream is not believed (a stray or corrupt segment).
constexpr std::int64_t kMaxAckAhead = 16 << 20;

std::int64_t seq_distance(std::uint32_t from, std::uint32_t to) {
  return static_cast<std::int32_t>(to - from);
}

}  // namespace

void TcpDirectionStream::on_segment(std::uint32_t seq, std::span<const std::uint8_t> payload,
                                    std::uint32_t on_wire, bool syn, bool fin, double time) {
  if (syn) {
    // The SYN takes one sequence number; data starts after it. A repeated SYN changes nothing
    // once data has flowed.
    if (!started_ || (next_offset_ == 0 && pending_.empty())) {
      started_ = true;
      next_seq_ = seq + 1;
    }
    return;
  }
  if (!started_) {
    started_ = true;  // the capture began inside the connection
    next_seq_ = seq;
  }
  if (fin) {
    fin_seen_ = true;
    fin_seq_ = seq + on_wire;
  }
  if (on_wire == 0) return;
  std::int64_t at = seq_distance(next_seq_, seq);
  if (at + on_wire <= 0) {
    stats_.retransmitted_bytes += on_wire;
    return;
  }
  if (at < 0) {
    // Partly seen already: keep the new tail only.
    const auto old = static_cast<std::uint32_t>(-at);
    stats_.retransmitted_bytes += old;
    payload = payload.subspan(std::min<std::size_t>(old, payload.size()));
    on_wire -= old;
    at = 0;
  }
  if (at == 0) {
    deliver(payload, on_wire, time);
    drain();
    return;
  }
  ++stats_.out_of_order_segments;
  store(next_offset_ + static_cast<std::uint64_t>(at), payload, on_wire, time);
  if (pending_bytes_ > limits_.max_buffered || pending_.size() > limits_.max_segments) {
    give_up_hole(time);
  }
}

void TcpDirectionStream::deliver(std::span<const std::uint8_t> bytes, std::uint32_t on_wire,
                                 double time) {
  if (!bytes.empty()) {
    sink_.on_stream_data(bytes, time);
    last_data_time_ = time;
    delivered_any_ = true;
  }
  stats_.delivered_bytes += bytes.size();
  next_seq_ += static_cast<std::uint32_t>(bytes.size());
  next_offset_ += bytes.size();
  // The snap length cut the segment: the rest of it is lost to the capture.
  if (on_wire > bytes.size()) skip(on_wire - bytes.size(), time);
}

void TcpDirectionStream::store(std::uint64_t offset, std::span<const std::uint8_t> bytes,
                               std::uint32_t on_wire, double time) {
  auto [it, inserted] = pending_.try_emplace(offset);
  if (!inserted) {
    // The same start again: keep the longer copy.
    if (it->second.on_wire >= on_wire) {
      stats_.retransmitted_bytes += on_wire;
      return;
    }
    stats_.retransmitted_bytes += it->second.on_wire;
    pending_bytes_ -= it->second.bytes.size();
  }
  it->second.bytes.assign(bytes.begin(), bytes.end());
  it->second.on_wire = on_wire;
  it->second.time = time;
  pending_bytes_ += bytes.size();
}

void TcpDirectionStream::drain() {
  while (!pending_.empty() && pending_.begin()->first <= next_offset_) {
    auto node = pending_.extract(pending_.begin());
    Pending& p = node.mapped();
    pending_bytes_ -= p.bytes.size();
    const std::uint64_t end = node.key() + p.on_wire;
    if (end <= next_offset_) {
      stats_.retransmitted_bytes += p.on_wire;
      continue;
    }
    const auto old = static_cast<std::uint32_t>(next_offset_ - node.key());
    stats_.retransmitted_bytes += old;
    const auto bytes =
        std::span<const std::uint8_t>(p.bytes).subspan(std::min<std::size_t>(old, p.bytes.size()));
    deliver(bytes, p.on_wire - old, p.time);
  }
}

void TcpDirectionStream::skip(std::uint64_t lost, double time) {
  next_seq_ += static_cast<std::uint32_t>(lost);
  next_offset_ += lost;
  stats_.lost_bytes += lost;
  ++stats_.gaps;
  sink_.on_stream_gap(lost, delivered_any_ ? std::min(time, last_data_time_) : time);
}

void TcpDirectionStream::give_up_hole(double time) {
  if (pending_.empty()) return;
  skip(pending_.begin()->first - next_offset_, time);
  drain();
}

void TcpDirectionStream::on_peer_ack(std::uint32_t ack, double time) {
  if (!started_) return;
  // The acknowledgement of our FIN covers one sequence number that carries no byte.
  if (fin_seen_ && ack == fin_seq_ + 1) ack = fin_seq_;
  const std::int64_t ahead = seq_distance(next_seq_, ack);
  if (ahead <= 0 || ahead > kMaxAckAhead) return;
  if (!pending_.empty()) {
    // The receiver has bytes up to `ack`: the hole before the first waiting segment is lost.
    if (pending_.begin()->first <= next_offset_ + static_cast<std::uint64_t>(ahead)) {
      give_up_hole(time);
    }
    return;
  }
  skip(static_cast<std::uint64_t>(ahead), time);  // the last segments were never captured
}

std::optional<double> TcpDirectionStream::hole_deadline() const {
  if (pending_.empty()) return std::nullopt;
  double oldest = pending_.begin()->second.time;
  for (const auto& entry : pending_) oldest = std::min(oldest, entry.second.time);
  // Given up once it has waited longer than hole_wait, not at it; expire() compares with
  // this very value, so that a wake at the deadline always acts.
  return std::nextafter(oldest + limits_.hole_wait, std::numeric_limits<double>::infinity());
}

void TcpDirectionStream::expire(double now) {
  for (std::optional<double> due = hole_deadline(); due && now >= *due; due = hole_deadline()) {
    give_up_hole(now);
  }
}

void TcpDirectionStream::flush(double time) {
  while (!pending_.empty()) give_up_hole(time);
}

}  // namespace pvtap
