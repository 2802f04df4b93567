// The end-to-end test captures: every input kind, every dialect, known content.
#include "test_captures.h"

#include <pcap/pcap.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <stdexcept>

#include "expectation_file.h"
#include "gateway_render.h"
#include "inverter_traffic.h"
#include "pvtap/codec/function_codes.h"
#include "pvtap/pcap/capture_writer.h"
#include "serial_render.h"

namespace pvtap::forge {
namespace {

constexpr double kStart = 1790000000.0;  // 2026-09-21, a fixed point so outputs are stable
constexpr double kRoundPeriod = 5.0;

// A plan of `rounds` poll rounds with the given faults per round; the last round is clean.
BusPlan site_plan(unsigned rounds, const std::vector<RoundFaults>& faults) {
  BusPlan plan;
  for (unsigned r = 0; r < rounds; ++r) {
    const RoundFaults f = r < faults.size() ? faults[r] : RoundFaults{};
    poll_round(plan, kStart + kRoundPeriod * r, r, f);
  }
  expect_round_values(plan, rounds - 1);
  return plan;
}

std::string path_in(const std::string& dir, const std::string& name) {
  return dir + "/" + name;
}

void save(const std::string& dir, const std::string& name, const Expected& e) {
  write_expectation(path_in(dir, name + ".expect.json"), e);
}

// Every Hybrid reply comes in two segments, as a gateway's packing timer cuts 81 bytes.
void split_hybrid_replies(GatewayRender& g, const BusPlan& plan) {
  for (std::size_t i = 0; i < plan.items().size(); ++i) {
    const BusItem& item = plan.items()[i];
    if (item.dialect == Dialect::Hybrid && item.role == Role::Response && item.is_frame &&
        item.bytes.size() > 40) {
      g.split(g.segment_of(i), 30);
    }
  }
}

// LossyPlan: six poll rounds with a fault each, a back-to-back pair of requests after round
// 0, and a station polled once at the end; where each round's items start in the plan.
struct LossyPlan {
  BusPlan plan;
  std::vector<std::size_t> round_start;
  std::size_t lonely = 0;  // the request to the station polled once
};

LossyPlan lossy_plan() {
  LossyPlan l;
  std::vector<RoundFaults> faults(6);
  faults[1].hybrid_bad_crc = true;
  faults[2].gsl2_silent = true;
  faults[3].gsl2_exception = true;
  faults[4].noise_after_ascii = true;
  faults[4].hybrid_error_reply = true;
  double t = kStart;
  for (unsigned r = 0; r < 6; ++r) {
    l.round_start.push_back(l.plan.items().size());
    t = poll_round(l.plan, kStart + kRoundPeriod * r, r, faults[r]);
    if (r != 0) continue;
    // Two requests sent back to back, answered back to back.
    const double a = t + 0.1;
    const double ct = l.plan.char_time();
    l.plan.exchange_at(a, gsl_read(1, 1056, 1), a + 0.030, gsl_reply(1, {5003}));
    l.plan.exchange_at(a + 8 * ct, gsl_read(2, 1033, 1), a + 0.030 + 7 * ct + 0.002,
                       gsl_reply(2, {0x0830}));
  }
  l.lonely = l.plan.items().size();
  l.plan.exchange(t + 0.2, gsl_read(9, 1056, 1), gsl_reply(9, {4998}), 0.020);
  expect_round_values(l.plan, 5);
  return l;
}

// Ethernet TCP with everything reassembly must survive: split, merged, reordered, repeated,
// overlapping and lost segments, and a gateway sequence number that wraps around zero.
void eth_tcp(const std::string& dir) {
  const LossyPlan l = lossy_plan();
  const BusPlan& plan = l.plan;
  const auto& round = l.round_start;
  GatewayRender g(plan, GatewayLayout{});
  split_hybrid_replies(g, plan);
  // Round 0: the back-to-back pair travels in one segment each way.
  const std::size_t pair = plan.find(round[1] - 4, Dialect::Gsl, Role::Request, 1);
  g.merge_with_next(g.segment_of(pair));
  g.merge_with_next(g.segment_of(pair + 1));
  // Round 2: the second half of the Hybrid reply is captured before the first.
  g.swap_with_next(g.segment_of(plan.find(round[2], Dialect::Hybrid, Role::Response, 6)));
  // Round 3: a reply repeated, a request resent with bytes before it, half a reply lost.
  g.retransmit(g.segment_of(plan.find(round[3], Dialect::Gsl, Role::Response, 1)), 0.2);
  const std::size_t ascii3 = plan.find(round[3], Dialect::Ascii, Role::Request, 3);
  g.split(g.segment_of(ascii3), 6, 0.0005);
  g.overlap_previous(g.segment_of(ascii3) + 1, 3);
  g.lose(g.segment_of(plan.find(round[3], Dialect::Hybrid, Role::Response, 6)) + 1);
  // Round 4: the ASCII reply and the noise after it in one segment.
  g.merge_with_next(g.segment_of(plan.find(round[4], Dialect::Ascii, Role::Response, 3)));
  // The lonely station's request is lost: its reply is unsolicited.
  g.lose(g.segment_of(l.lonely));

  PcapCaptureWriter out(path_in(dir, "eth_tcp.pcap"), link_type_of(LinkLayer::Ethernet));
  save(dir, "eth_tcp", g.write(out));
}

void gateway_capture(const std::string& dir, const std::string& name, const BusPlan& plan,
                     GatewayLayout layout, bool pcapng, std::vector<std::string> args = {}) {
  GatewayRender g(plan, layout);
  split_hybrid_replies(g, plan);
  auto out = open_capture_writer(path_in(dir, name), link_type_of(layout.link), pcapng);
  Expected e = g.write(*out);
  e.args = std::move(args);
  const std::string stem = name.substr(0, name.find('.'));
  save(dir, stem, e);
}

void link_layer_captures(const std::string& dir) {
  std::vector<RoundFaults> faults(3);
  GatewayLayout layout;
  layout.gateway.port = 8899;
  gateway_capture(dir, "eth_clean.pcapng", site_plan(3, {}), layout, true);

  faults[1].hybrid_bad_crc = true;
  layout.link = LinkLayer::Sll;
  gateway_capture(dir, "sll_tcp.pcap", site_plan(3, faults), layout, false);

  faults[1] = RoundFaults{};
  faults[1].gsl2_exception = true;
  GatewayLayout v6;
  v6.link = LinkLayer::Sll2;
  v6.master = ipv6_endpoint(1, 50200);
  v6.gateway = ipv6_endpoint(2, 4001);
  gateway_capture(dir, "sll2_tcp6.pcap", site_plan(3, faults), v6, false);

  faults[1] = RoundFaults{};
  faults[1].gsl2_silent = true;
  layout.link = LinkLayer::Raw;
  layout.gateway.port = 4001;
  gateway_capture(dir, "raw_tcp.pcap", site_plan(3, faults), layout, false);

  // Captured in the middle of the connection: no handshake; the gateway's lower port tells.
  GatewayLayout loop;
  loop.link = LinkLayer::Loopback;
  loop.master = ipv4_endpoint(127, 0, 0, 1, 40000);
  loop.gateway = ipv4_endpoint(127, 0, 0, 1, 502);
  loop.handshake = false;
  gateway_capture(dir, "loopback_tcp.pcap", site_plan(3, {}), loop, false);

  GatewayLayout udp;
  udp.udp = true;
  udp.gateway.port = 8899;
  gateway_capture(dir, "eth_udp.pcap", site_plan(3, {}), udp, false);
}

// A gateway flow among other traffic: a web download and ARP. Without --port the flow is
// recognized by its frames; with --port 4001 it is chosen; with --port 80 nothing is found.
void other_traffic(const std::string& dir) {
  const BusPlan plan = site_plan(3, {});
  PcapCaptureWriter out(path_in(dir, "eth_other_traffic.pcap"), link_type_of(LinkLayer::Ethernet));
  out.write(kStart - 3.0, arp_packet());
  const Endpoint browser = ipv4_endpoint(10, 0, 0, 1, 51000);
  const Endpoint web = ipv4_endpoint(10, 0, 0, 9, 80);
  std::string page = "HTTP/1.1 200 OK\r\nContent-Type: text/html\r\n\r\n";
  while (page.size() < 4000) page += "<p>inverter portal, nothing to see on the bus</p>\n";
  const std::string request = "GET / HTTP/1.1\r\nHost: portal\r\n\r\n";
  const Bytes get(request.begin(), request.end());
  const Bytes body(page.begin(), page.end());
  out.write(kStart - 2.0,
            tcp_packet(LinkLayer::Ethernet, {browser, web}, {100, 0, tcp_flag::kSyn}, {}));
  out.write(kStart - 1.99, tcp_packet(LinkLayer::Ethernet, {web, browser},
                                      {7000, 101, tcp_flag::kSyn | tcp_flag::kAck}, {}));
  out.write(kStart - 1.98,
            tcp_packet(LinkLayer::Ethernet, {browser, web}, {101, 7001, tcp_flag::kAck}, get));
  for (std::size_t at = 0; at < body.size(); at += 1400) {
    const std::size_t n = std::min<std::size_t>(1400, body.size() - at);
    out.write(
        kStart - 1.9 + 0.001 * static_cast<double>(at / 1400),
        tcp_packet(LinkLayer::Ethernet, {web, browser},
                   {7001 + static_cast<std::uint32_t>(at),
                    101 + static_cast<std::uint32_t>(get.size()), tcp_flag::kAck | tcp_flag::kPsh},
                   std::span(body).subspan(at, n)));
  }
  GatewayRender g(plan, GatewayLayout{});
  Expected e = g.write(out);
  save(dir, "eth_other_traffic", e);
  e.args = {"--port", "4001"};
  save(dir, "eth_other_traffic.port", e);
  Expected none;  // the web download read as a bus: all noise
  const std::uint64_t web_bytes = get.size() + body.size();
  none.counts = {{"frames", 0}, {"bytes", web_bytes}, {"noise_bytes", web_bytes}};
  none.args = {"--port", "80"};
  save(dir, "eth_other_traffic.wrong_port", none);
}

// USER0 chunks of a 16 ms latency timer, the same bus as a plain dump, and the USER0
// capture again with only the Hybrid dialect recognized.
void user0_and_raw(const std::string& dir) {
  std::vector<RoundFaults> faults(4);
  faults[0].noise_after_ascii = true;
  faults[1].hybrid_bad_crc = true;
  faults[1].gsl2_silent = true;
  faults[2].gsl2_exception = true;
  faults[2].hybrid_error_reply = true;
  const BusPlan plan = site_plan(4, faults);
  {
    PcapCaptureWriter out(path_in(dir, "user0.pcap"), DLT_USER0);
    write_timer_chunks(plan, out);
  }
  save(dir, "user0", plan.expected());
  write_raw_dump(plan, path_in(dir, "raw.bin"));
  Expected raw = plan.expected();
  raw.args = {"--raw"};
  save(dir, "raw", raw);

  Expected hybrid_only = plan.expected({}, DialectSet::only(Dialect::Hybrid));
  hybrid_only.values = {hybrid_only.values[3]};
  // With only Hybrid recognized, the ASCII request after the corrupted reply is noise; the
  // silence before it (longer than the adapter's latency plus t3.5) still pins the reply's
  // end, so the reply is a bad-check frame that answers its request, not a timeout.
  hybrid_only.args = {"--dialect", "hybrid"};
  save(dir, "user0.hybrid_only", hybrid_only);
}

// RTAC: one exchange of round 1 never reached the capture (a CAPTURE_DATA_LOST record).
void rtac(const std::string& dir) {
  const BusPlan plan = site_plan(3, {});
  const std::size_t gsl2 = plan.find(0, Dialect::Gsl, Role::Request, kGslStation2);
  const std::size_t dropped = plan.find(gsl2 + 1, Dialect::Gsl, Role::Request, kGslStation2);
  {
    PcapCaptureWriter out(path_in(dir, "rtac.pcap"), DLT_RTAC_SERIAL);
    write_rtac_records(plan, out, 5, {dropped, dropped + 1});
  }
  const std::vector<std::uint64_t> offsets = plan.stream_offsets(false);
  const std::uint64_t lost_end = offsets[dropped + 1] + plan.items()[dropped + 1].bytes.size();
  Expected e = plan.expected({{Direction::Unknown, offsets[dropped], lost_end}});
  e.counts["lost_bytes"] = 0;  // RTAC says that data was lost, not how much
  save(dir, "rtac", e);
}

// GSL registers read by hex IDs (ID 1056 sent as 0x1056), decoded with --gsl-ids hex, and a
// user map that extends the Hybrid map (battery voltage in 0.01 V).
void decoder_options(const std::string& dir) {
  BusPlan plan;
  plan.exchange(kStart, gsl_read(1, 0x1050, 7),
                gsl_reply(1, {4000, 4001, 3999, 120, 121, 119, 5002}), 0.030);
  plan.exchange(kStart + 1, hybrid_read(6, 0x12, 0x1000, 0x24),
                hybrid_reply(6, 0x12, hybrid_running_data(7)), 0.050);
  plan.expect_value("1", "1056", 50.02);
  plan.expect_value("6", "0x1006", 5.30);
  {
    PcapCaptureWriter out(path_in(dir, "options.pcap"), DLT_USER1);
    write_timer_chunks(plan, out);
  }
  std::ofstream map(path_in(dir, "site_map.toml"));
  map << "dialect = \"hybrid\"\nmode = \"extend\"\n\n[[register]]\naddress = 0x1006\n"
         "key = \"battery_voltage\"\nname = \"battery voltage\"\nscale = 0.01\nunit = \"V\"\n";
  Expected e = plan.expected();
  e.args = {"--gsl-ids", "hex", "--map", "{dir}/site_map.toml"};
  save(dir, "options", e);
}

// An energy meter (station 10, float32 input registers) beside a GSL inverter: decoded with a
// map given to its station only. Voltages high word first, the energy low word first.
Frame meter_read(std::uint16_t start, std::uint16_t count) {
  Frame f = make_frame(Dialect::Modbus, Role::Request, 10, fc::kGslReadInput);
  f.start = start;
  f.count = count;
  return f;
}

Frame meter_reply(const WordList& words) {
  Frame f = make_frame(Dialect::Modbus, Role::Response, 10, fc::kGslReadInput);
  f.byte_count = static_cast<std::uint8_t>(2 * words.size());
  f.words = words;
  return f;
}

void station_map(const std::string& dir) {
  BusPlan plan;
  double at = plan.exchange(kStart, gsl_read(1, 1050, 7),
                            gsl_reply(1, {2301, 2302, 2299, 120, 121, 119, 5002}), 0.030);
  // 230.1 V, 231.4 V, 229.8 V.
  at = plan.exchange(at + 0.05, meter_read(0x0000, 6),
                     meter_reply({0x4366, 0x199A, 0x4367, 0x6666, 0x4365, 0xCCCD}), 0.020);
  // 49.98 Hz; 1234.5 kWh as 0x449A5000, low word first.
  plan.exchange(at + 0.05, meter_read(0x0046, 4), meter_reply({0x4247, 0xEB85, 0x5000, 0x449A}),
                0.020);
  plan.expect_value("1", "1050", 230.1);
  plan.expect_value("10", "0x0000", 230.1);
  plan.expect_value("10", "0x0004", 229.8);
  plan.expect_value("10", "0x0046", 49.98);
  plan.expect_value("10", "0x0048", 1234.5);
  {
    PcapCaptureWriter out(path_in(dir, "station_map.pcap"), DLT_USER1);
    write_timer_chunks(plan, out);
  }
  std::ofstream map(path_in(dir, "meter.toml"));
  map << "dialect = \"modbus\"\n";
  for (const char* entry : {"0x0000\nkey = \"v1\"\nname = \"voltage 1\"\nunit = \"V\"",
                            "0x0004\nkey = \"v3\"\nname = \"voltage 3\"\nunit = \"V\"",
                            "0x0046\nkey = \"hz\"\nname = \"frequency\"\nunit = \"Hz\"",
                            "0x0048\nkey = \"kwh\"\nname = \"energy\"\nword_order = "
                            "\"low_first\""}) {
    map << "\n[[register]]\nkind = \"float32\"\naddress = " << entry << "\n";
  }
  Expected e = plan.expected();
  e.args = {"--map", "10={dir}/meter.toml"};
  save(dir, "station_map", e);
}

void bad_inputs(const std::string& dir) {
  std::ofstream(path_in(dir, "not_a_capture.txt")) << "time,station,value\n1,2,3\n";
  std::ofstream(path_in(dir, "empty.pcap"));
  {
    PcapCaptureWriter out(path_in(dir, "unsupported.pcap"), DLT_IEEE802_11);
    out.write(kStart, Bytes(24, 0));
  }
  // user0.pcap cut in the middle of a record.
  std::ifstream in(path_in(dir, "user0.pcap"), std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::ofstream(path_in(dir, "truncated.pcap"), std::ios::binary)
      << bytes.substr(0, bytes.size() / 2 + 7);
  std::ofstream(path_in(dir, "bad_map.toml"))
      << "dialect = \"hybrid\"\n[[register]]\naddress = 1\n";
}

}  // namespace

void write_test_captures(const std::string& dir) {
  eth_tcp(dir);
  link_layer_captures(dir);
  other_traffic(dir);
  user0_and_raw(dir);
  rtac(dir);
  decoder_options(dir);
  station_map(dir);
  bad_inputs(dir);
}

}  // namespace pvtap::forge
