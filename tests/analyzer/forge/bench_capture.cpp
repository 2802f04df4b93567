// The benchmark capture: a gateway stream of poll rounds, written packet by packet.
#include <pcap/pcap.h>

#include "gateway_render.h"
#include "inverter_traffic.h"
#include "pvtap/carriers/solarman_v5_frame.h"
#include "pvtap/pcap/capture_writer.h"
#include "test_captures.h"

namespace pvtap::forge {
namespace {

constexpr double kBenchStart = 1790000000.0;

// BenchStream: one TCP connection written packet by packet, for captures too big to plan.
class BenchStream {
 public:
  BenchStream(CaptureWriter& out, const GatewayLayout& layout) : out_(out), g_(layout) {}

  void handshake(double t) {
    out_.write(t, tcp_packet(g_.link, {g_.master, g_.gateway}, {mseq_ - 1, 0, tcp_flag::kSyn}, {}));
    out_.write(t + 1e-4, tcp_packet(g_.link, {g_.gateway, g_.master},
                                    {sseq_ - 1, mseq_, tcp_flag::kSyn | tcp_flag::kAck}, {}));
    out_.write(t + 2e-4,
               tcp_packet(g_.link, {g_.master, g_.gateway}, {mseq_, sseq_, tcp_flag::kAck}, {}));
  }
  // One data segment and the receiver's acknowledgement.
  void send(bool to_gateway, std::span<const std::uint8_t> bytes, double t) {
    const Endpoint& from = to_gateway ? g_.master : g_.gateway;
    const Endpoint& to = to_gateway ? g_.gateway : g_.master;
    std::uint32_t& seq = to_gateway ? mseq_ : sseq_;
    const std::uint32_t peer = to_gateway ? sseq_ : mseq_;
    out_.write(
        t, tcp_packet(g_.link, {from, to}, {seq, peer, tcp_flag::kAck | tcp_flag::kPsh}, bytes));
    seq += static_cast<std::uint32_t>(bytes.size());
    out_.write(t + 3e-4, tcp_packet(g_.link, {to, from}, {peer, seq, tcp_flag::kAck}, {}));
  }

 private:
  CaptureWriter& out_;
  GatewayLayout g_;
  std::uint32_t mseq_ = 1000001;
  std::uint32_t sseq_ = 0xFFFFFF01;
};

// A logger stick's V5 frame around one transmission; every fifth reply with the two zeros.
Bytes v5_wrapped(const BusItem& item, std::uint16_t sequence) {
  namespace v5 = solarman_v5;
  const bool request = item.direction == Direction::ToSlave;
  const Bytes payload = request ? v5::request_payload(item.bytes)
                                : v5::response_payload(item.bytes, sequence % 5 == 4);
  return v5::encode_frame(v5::Header{0, request ? v5::control::kRequest : v5::control::kResponse,
                                     sequence, 2712345678u},
                          payload);
}

// The same poll rounds through a logger stick: one V5 frame per segment; noise on the line
// never reaches the LAN.
void write_v5_rounds(BenchStream& stream, double t, std::uint64_t target) {
  std::uint64_t written = 24;
  std::uint16_t sequence = 0;
  for (unsigned round = 0; written < target; ++round) {
    RoundFaults faults;
    faults.gsl2_silent = round % 101 == 7;
    faults.gsl2_exception = round % 89 == 3;
    BusPlan plan;
    t = poll_round(plan, t, round, faults);
    for (const BusItem& item : plan.items()) {
      if (!item.is_frame) continue;
      if (item.direction == Direction::ToSlave) ++sequence;
      const Bytes frame = v5_wrapped(item, sequence);
      stream.send(item.direction == Direction::ToSlave, frame, item.end + 2e-4);
      written += 2 * (16 + 54) + 6 + frame.size();
    }
    t += 0.2;
  }
}

}  // namespace

void write_v5_bench_capture(const std::string& path, unsigned megabytes) {
  PcapCaptureWriter out(path, DLT_EN10MB);
  GatewayLayout layout;
  layout.gateway.port = 8899;
  BenchStream stream(out, layout);
  stream.handshake(kBenchStart - 0.01);
  write_v5_rounds(stream, kBenchStart, std::uint64_t{megabytes} << 20);
}

void write_bench_capture(const std::string& path, unsigned megabytes) {
  PcapCaptureWriter out(path, DLT_EN10MB);
  BenchStream stream(out, GatewayLayout{});
  stream.handshake(kBenchStart - 0.01);
  const std::uint64_t target = std::uint64_t{megabytes} << 20;
  std::uint64_t written = 24;  // pcap file header
  double t = kBenchStart;
  for (unsigned round = 0; written < target; ++round) {
    RoundFaults faults;
    faults.hybrid_bad_crc = round % 97 == 5;
    faults.gsl2_silent = round % 101 == 7;
    faults.gsl2_exception = round % 89 == 3;
    faults.noise_after_ascii = round % 53 == 1;
    BusPlan plan;
    t = poll_round(plan, t, round, faults);
    for (const BusItem& item : plan.items()) {
      const bool to_gateway = item.direction == Direction::ToSlave;
      const std::span<const std::uint8_t> bytes(item.bytes);
      if (!to_gateway && bytes.size() > 40) {
        stream.send(false, bytes.first(30), item.end - 0.01);
        stream.send(false, bytes.subspan(30), item.end + 2e-4);
      } else {
        stream.send(to_gateway, bytes, item.end + 2e-4);
      }
      // Two packets per segment: 16-byte record headers, 54 bytes of headers (60 minimum).
      written += 2 * (16 + 54) + 6 + bytes.size() + (bytes.size() > 40 ? 16 + 54 + 16 + 60 : 0);
    }
    t += 0.2;
  }
}

}  // namespace pvtap::forge
