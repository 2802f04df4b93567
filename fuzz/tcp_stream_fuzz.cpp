// Fuzz target tcp_stream: one direction of a TCP connection fed segments chosen by the fuzzer:
// any sequence numbers (relative to a chosen initial one, so wraps are near), overlaps,
// repeats, snap-length cuts, SYN and FIN anywhere, acknowledgements, expiry and RST (flush).
// Asserts that every byte handed on was captured once and that the counts add up.
//
// Layout: initial sequence number (4 bytes), a limits byte, then records of
//   flags (bit 0 SYN, 1 FIN, 2 the record is a peer ACK, 3 expire holes, 4 RST: flush),
//   sequence offset (4 bytes), captured length (1 byte), bytes cut by the snap length
//   (1 byte; bit 7 set: times 256), time (1 byte, 10 ms units; 255 sets the clock back), payload.
#include <cstddef>
#include <cstdint>
#include <span>

#include "fuzz_input.h"
#include "pvtap/carriers/tcp_stream.h"

namespace {

using pvtap::TcpDirectionStream;

class CountingSink : public pvtap::TcpStreamSink {
 public:
  void on_stream_data(std::span<const std::uint8_t> bytes, double) override {
    PVTAP_FUZZ_CHECK(!bytes.empty());
    delivered += bytes.size();
  }
  void on_stream_gap(std::uint64_t lost_bytes, double) override {
    lost += lost_bytes;
    ++gaps;
  }
  std::uint64_t delivered = 0;
  std::uint64_t lost = 0;
  std::uint64_t gaps = 0;
};

struct Clock {
  double now = 1.0e9;
  void tick(std::uint8_t t) { now = t == 255 ? now - 5.0 : now + t * 0.01; }
};

void step(pvtap::fuzz::FuzzInput& in, std::uint32_t initial, TcpDirectionStream& stream,
          Clock& clock, std::uint64_t& captured) {
  const std::uint8_t flags = in.byte();
  const std::uint32_t seq = initial + in.u32();
  const std::uint8_t length = in.byte();
  const std::uint8_t cut = in.byte();
  clock.tick(in.byte());
  const auto payload = in.take(length);
  const std::uint32_t missing = (cut & 0x80u) ? (cut & 0x7Fu) * 256u : cut;
  if (flags & 4u) {
    stream.on_peer_ack(seq, clock.now);
  } else {
    stream.on_segment(seq, payload, static_cast<std::uint32_t>(payload.size()) + missing,
                      (flags & 1u) != 0, (flags & 2u) != 0, clock.now);
    captured += payload.size();
  }
  if (flags & 8u) stream.expire(clock.now);
  if (flags & 16u) stream.flush(clock.now);
}

void check_counts(const TcpDirectionStream& stream, const CountingSink& sink,
                  std::uint64_t captured) {
  const auto& s = stream.stats();
  PVTAP_FUZZ_CHECK(s.delivered_bytes == sink.delivered);
  PVTAP_FUZZ_CHECK(s.lost_bytes == sink.lost);
  PVTAP_FUZZ_CHECK(s.gaps == sink.gaps);
  PVTAP_FUZZ_CHECK(sink.delivered <= captured);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  pvtap::fuzz::FuzzInput in(data, size);
  const std::uint32_t initial = in.u32();
  TcpDirectionStream::Limits limits;
  limits.max_buffered = std::size_t{256} << (in.byte() & 7u);
  CountingSink sink;
  TcpDirectionStream stream(sink, limits);
  Clock clock;
  std::uint64_t captured = 0;
  while (!in.empty()) {
    step(in, initial, stream, clock, captured);
    check_counts(stream, sink, captured);
  }
  stream.flush(clock.now);
  check_counts(stream, sink, captured);
  PVTAP_FUZZ_CHECK(!stream.has_hole());
  return 0;
}
