// Reassembly of one direction of a TCP connection into its byte stream, in sequence order.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <vector>

namespace pvtap {

// TcpStreamSink: receives one direction's bytes in stream order, and the holes that were
// never filled (capture data loss) with their size.
class TcpStreamSink {
 public:
  virtual ~TcpStreamSink() = default;
  virtual void on_stream_data(std::span<const std::uint8_t> bytes, double time) = 0;
  virtual void on_stream_gap(std::uint64_t lost_bytes, double time) = 0;
};

// TcpStreamStats: what reassembly had to repair.
struct TcpStreamStats {
  std::uint64_t delivered_bytes = 0;
  std::uint64_t retransmitted_bytes = 0;  // bytes seen again and dropped (overlaps included)
  std::uint64_t out_of_order_segments = 0;
  std::uint64_t lost_bytes = 0;
  std::uint64_t gaps = 0;
};

// TcpDirectionStream: one direction of a connection. Segments may come out of order,
// repeated or overlapping; each stream byte is delivered once, in order. A hole is given up
// as lost when the peer acknowledges data beyond it (the receiver got bytes the capture
// missed), when it stays open longer than `hole_wait` seconds of capture time, when more than
// `max_buffered` bytes or `max_segments` segments wait behind it, or at the end.
class TcpDirectionStream {
 public:
  struct Limits {
    double hole_wait = 2.0;
    std::size_t max_buffered = 1 << 20;
    // Each waiting segment costs about 100 bytes besides its payload: without this limit a
    // million one-byte segments behind a hole would hold over 100 MB within max_buffered.
    std::size_t max_segments = 4096;
  };

  TcpDirectionStream(TcpStreamSink& sink, Limits limits) : sink_(sink), limits_(limits) {}
  explicit TcpDirectionStream(TcpStreamSink& sink) : TcpDirectionStream(sink, Limits{}) {}

  // `payload` is the captured part of a segment whose payload is `on_wire` bytes long.
  void on_segment(std::uint32_t seq, std::span<const std::uint8_t> payload, std::uint32_t on_wire,
                  bool syn, bool fin, double time);
  // An acknowledgement sent by the other side.
  void on_peer_ack(std::uint32_t ack, double time);
  // Gives up the holes whose deadline has come.
  void expire(double now);
  // When the oldest waiting segment has waited `hole_wait`, the hole before it is given up:
  // the next time expire() acts, so that a live capture gives up a hole while nothing arrives.
  // nullopt while nothing waits.
  std::optional<double> hole_deadline() const;
  // End of the connection or the capture: every hole is lost, every byte delivered.
  void flush(double time);

  bool has_hole() const { return !pending_.empty(); }
  const TcpStreamStats& stats() const { return stats_; }

 private:
  struct Pending {
    std::vector<std::uint8_t> bytes;  // captured
    std::uint32_t on_wire = 0;
    double time = 0;
  };

  void deliver(std::span<const std::uint8_t> bytes, std::uint32_t on_wire, double time);
  void store(std::uint64_t offset, std::span<const std::uint8_t> bytes, std::uint32_t on_wire,
             double time);
  void drain();
  void give_up_hole(double time);
  void skip(std::uint64_t lost, double time);

  TcpStreamSink& sink_;
  Limits limits_;
  bool started_ = false;
  std::uint32_t next_seq_ = 0;     // sequence number of the next stream byte
  std::uint64_t next_offset_ = 0;  // its stream offset
  bool fin_seen_ = false;
  std::uint32_t fin_seq_ = 0;
  std::map<std::uint64_t, Pending> pending_;  // by stream offset
  // When the last delivered bytes arrived: a hole is placed there, where data went missing,
  // rather than where the loss was noticed.
  double last_data_time_ = 0;
  bool delivered_any_ = false;
  std::size_t pending_bytes_ = 0;
  TcpStreamStats stats_;
};

}  // namespace pvtap
