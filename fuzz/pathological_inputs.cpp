// pvtap-pathological: inputs that are valid but extreme (issue 12, point 3), each timed and
// measured: `pvtap-pathological CASE|all [SCALE]`. SCALE 1 is the size; the CTest
// test runs a small scale. Every case checks that each byte is accounted for and prints the
// time, the rate and the growth of the peak resident memory.
#include <pcap/pcap.h>
#include <sys/resource.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>
#include <vector>

#include "cli/audit_command.h"
#include "cli/common_options.h"
#include "cli/exit_status.h"
#include "fuzz_input.h"
#include "pvtap/carriers/tcp_stream.h"
#include "pvtap/codec/frame_codec.h"
#include "pvtap/pcap/capture_writer.h"
#include "pvtap/pcap/exported_pdu_reader.h"
#include "pvtap/pcap/packet_builder.h"
#include "pvtap/pcap/rtac_record.h"
#include "pvtap/registers/register_map.h"
#include "pvtap/session/bus_session.h"

namespace {

using pvtap::TcpDirectionStream;
using Bytes = std::vector<std::uint8_t>;

long peak_rss_kb() {
  rusage u{};
  ::getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss;
}

struct StreamCount : pvtap::TcpStreamSink {
  void on_stream_data(std::span<const std::uint8_t> b, double) override { delivered += b.size(); }
  void on_stream_gap(std::uint64_t lost_bytes, double) override { lost += lost_bytes; }
  std::uint64_t delivered = 0;
  std::uint64_t lost = 0;
};

// One million one-byte segments of one direction, in reverse order, after the SYN.
std::uint64_t tcp_reverse(double scale) {
  const auto n = static_cast<std::uint32_t>(1'000'000 * scale);
  StreamCount sink;
  TcpDirectionStream stream(sink);
  const std::uint32_t isn = 0xFFFF0000;  // the stream wraps on the way
  stream.on_segment(isn, {}, 0, true, false, 0);
  const std::uint8_t byte = 0x42;
  for (std::uint32_t i = n; i-- > 0;)
    stream.on_segment(isn + 1 + i, {&byte, 1}, 1, false, false, 0);
  stream.flush(1);
  PVTAP_FUZZ_CHECK(sink.delivered + sink.lost == n);
  return n;
}

// A sequence number jump of 2 GB in the middle of a stream.
std::uint64_t seq_jump(double) {
  StreamCount sink;
  TcpDirectionStream stream(sink);
  const Bytes data(1000, 0x11);
  std::uint32_t seq = 1000;
  stream.on_segment(seq - 1, {}, 0, true, false, 0);
  for (int i = 0; i < 100; ++i, seq += 1000) stream.on_segment(seq, data, 1000, false, false, i);
  seq += 0x80000000u;
  for (int i = 0; i < 100; ++i, seq += 1000) stream.on_segment(seq, data, 1000, false, false, i);
  stream.flush(200);
  PVTAP_FUZZ_CHECK(sink.delivered <= 200'000);
  PVTAP_FUZZ_CHECK(sink.delivered >= 100'000);
  return 200'000;
}

struct SessionCount : pvtap::BusSessionSink {
  void on_frame(const pvtap::SessionFrame& f) override { frame_bytes += f.bytes.size(); }
  void on_noise(const pvtap::SessionNoise& n) override { noise_bytes += n.noise.bytes.size(); }
  std::uint64_t frame_bytes = 0;
  std::uint64_t noise_bytes = 0;
};

// Bytes fed to a bus session in chunks of 64 KiB, all accounted for at the end.
std::uint64_t feed_session(std::uint64_t total, bool timed,
                           const std::function<void(Bytes&)>& fill) {
  static const pvtap::RegisterDecoder decoder;
  pvtap::BusSessionOptions o;
  o.has_timestamps = timed;
  if (!timed) o.reassembler.timestamps = pvtap::TimestampTrust::Untrusted;
  SessionCount sink;
  pvtap::BusSession session(o, decoder, sink);
  Bytes chunk(64 * 1024);
  double t = 1.0e9;
  for (std::uint64_t done = 0; done < total; done += chunk.size()) {
    fill(chunk);
    session.feed({chunk, t += 0.07, pvtap::Direction::Unknown});
  }
  session.finish();
  const auto totals = session.totals();
  PVTAP_FUZZ_CHECK(totals.bytes_in == totals.frame_bytes + totals.noise_bytes);
  PVTAP_FUZZ_CHECK(totals.frame_bytes == sink.frame_bytes);
  PVTAP_FUZZ_CHECK(totals.noise_bytes == sink.noise_bytes);
  return totals.bytes_in;
}

// 100 MB of random bytes on a bus with timestamps (noise, frames only by chance).
std::uint64_t noise(double scale) {
  std::uint64_t state = 88172645463325252ull;
  return feed_session(static_cast<std::uint64_t>(100e6 * scale), true, [&](Bytes& b) {
    for (auto& x : b) {
      state ^= state << 13, state ^= state >> 7, state ^= state << 17;
      x = static_cast<std::uint8_t>(state);
    }
  });
}

// `pvtap audit --raw` of 1 GB of 0x00: a session without timestamps.
std::uint64_t raw_zeros(double scale) {
  return feed_session(static_cast<std::uint64_t>(1e9 * scale), false,
                      [](Bytes& b) { std::fill(b.begin(), b.end(), 0); });
}

// A link-type-252 record of 65,535 bytes: tags, then a PDU of noise and one frame.
std::uint64_t pdu_65535(double) {
  Bytes record = {0, 12, 0, 8, 'p', 'v', 't', 'a', 'p', 0, 0, 0,
                  0, 35, 0, 4, 0,   0,   0,   0,   0,   0, 0, 0};
  pvtap::Frame request;
  request.dialect = pvtap::Dialect::Gsl;
  request.station = 1;
  request.function = 0x03;
  request.start = 0x041A;
  request.count = 10;
  const auto wire = pvtap::encode_frame(request);
  record.resize(65535 - wire.size(), 0x00);
  record.insert(record.end(), wire.begin(), wire.end());
  const auto pdu = pvtap::exported_pdu_record(record);
  PVTAP_FUZZ_CHECK(pdu && pdu->dissector == "pvtap" && pdu->pdu.size() == 65535 - 24);
  static const pvtap::RegisterDecoder decoder;
  SessionCount sink;
  pvtap::BusSession session({}, decoder, sink);
  session.feed({pdu->pdu, 1.0e9, pdu->direction});
  session.finish();
  PVTAP_FUZZ_CHECK(sink.frame_bytes == wire.size());
  PVTAP_FUZZ_CHECK(sink.noise_bytes + sink.frame_bytes == pdu->pdu.size());
  return record.size();
}

// A map file of 100,000 registers (more than the 65,536 addresses: the rest must be refused
// with a diagnostic each, not loaded or crashed on).
std::uint64_t map_registers(double scale) {
  const auto n = static_cast<unsigned>(100'000 * scale);
  std::string text = "dialect = \"hybrid\"\n";
  for (unsigned i = 0; i < n; ++i) {
    text += "[[register]]\naddress = " + std::to_string(i) + "\nkey = \"r" + std::to_string(i) +
            "\"\nname = \"r\"\nscale = 0.1\n";
  }
  const auto loaded = pvtap::load_register_map(text, "big.toml");
  if (n <= 65536) {
    PVTAP_FUZZ_CHECK(loaded && loaded->size() == n);
  } else {
    PVTAP_FUZZ_CHECK(!loaded && !loaded.diagnostics().empty());
  }
  return text.size();
}

// 10,000 gateway connections open at once: each connects, sends a request, and only when
// all are open do the replies come, then every connection closes.
std::uint64_t connections(double scale) {
  using namespace pvtap;
  const auto n = static_cast<unsigned>(10'000 * scale);
  char path[] = "/tmp/pvtap-pathological-XXXXXX";
  const int fd = ::mkstemp(path);
  PVTAP_FUZZ_CHECK(fd >= 0);
  ::close(fd);
  pvtap::Frame req;
  req.dialect = pvtap::Dialect::Gsl;
  req.station = 1;
  req.function = 0x03;
  req.start = 0x041A;
  req.count = 1;
  const auto wire = pvtap::encode_frame(req);
  {
    PcapCaptureWriter out(path, DLT_EN10MB);
    const Endpoint gateway = ipv4_endpoint(10, 0, 0, 2, 4001);
    double t = 1.0e9;
    auto master = [](unsigned i) {
      return ipv4_endpoint(10, 1, static_cast<std::uint8_t>(i >> 8), static_cast<std::uint8_t>(i),
                           static_cast<std::uint16_t>(20000 + i % 40000));
    };
    for (unsigned i = 0; i < n; ++i) {
      out.write(t += 1e-5,
                tcp_packet(LinkLayer::Ethernet, {master(i), gateway}, {99, 0, tcp_flag::kSyn}, {}));
      out.write(t += 1e-5, tcp_packet(LinkLayer::Ethernet, {master(i), gateway},
                                      {100, 0, tcp_flag::kAck | tcp_flag::kPsh}, wire));
    }
    for (unsigned i = 0; i < n; ++i) {
      out.write(t += 1e-5, tcp_packet(LinkLayer::Ethernet, {master(i), gateway},
                                      {108, 0, tcp_flag::kAck | tcp_flag::kFin}, {}));
    }
  }
  pvtap::analyzer::AuditOptions o;
  o.captures = {path};
  o.summary_only = true;
  pvtap::analyzer::apply_choices(o);
  static const pvtap::RegisterDecoder decoder;
  std::FILE* null = std::fopen("/dev/null", "w");
  int status = 0;
  {
    pvtap::analyzer::OutputStream out(null);
    status = pvtap::analyzer::audit(o, decoder, out);
  }
  std::fclose(null);
  ::unlink(path);
  PVTAP_FUZZ_CHECK(status == pvtap::analyzer::kExitOk);
  return n;
}

struct Case {
  const char* name;
  const char* unit;
  std::uint64_t (*run)(double);
};

constexpr Case kCases[] = {
    {"tcp_reverse", "segments", tcp_reverse},
    {"seq_jump", "bytes", seq_jump},
    {"connections", "connections", connections},
    {"noise", "bytes", noise},
    {"raw_zeros", "bytes", raw_zeros},
    {"pdu_65535", "bytes", pdu_65535},
    {"map_registers", "bytes of TOML", map_registers},
};

void run_case(const Case& c, double scale) {
  const long rss_before = peak_rss_kb();
  const auto start = std::chrono::steady_clock::now();
  const std::uint64_t size = c.run(scale);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("%-14s %12llu %-14s %8.2f s  %12.0f /s  peak RSS +%ld MB\n", c.name,
              static_cast<unsigned long long>(size), c.unit, seconds,
              static_cast<double>(size) / seconds, (peak_rss_kb() - rss_before) / 1024);
}

}  // namespace

int main(int argc, char** argv) {
  const std::string which = argc > 1 ? argv[1] : "all";
  const double scale = argc > 2 ? std::strtod(argv[2], nullptr) : 1.0;
  bool found = false;
  for (const Case& c : kCases) {
    if (which == "all" || which == c.name) {
      run_case(c, scale);
      found = true;
    }
  }
  if (!found) std::fprintf(stderr, "pvtap-pathological: no case %s\n", which.c_str());
  return found ? 0 : 2;
}
