#include "lan/tcp_session.h"

#include <pcap/pcap.h>

#include <algorithm>

#include "pvtap/pcap/packet_builder.h"
#include "pvtap/pcap/pcap_writer.h"

namespace pvtap::sim {
namespace {

const MacAddress kClientMac{0x02, 0, 0, 0, 0, 0x01};
const MacAddress kDeviceMac{0x02, 0, 0, 0, 0, 0x03};

struct Planned {
  LanSegment segment;
  std::uint8_t flags = tcp_flag::kAck;
};

void add_handshake(Micros first, Micros last, std::vector<Planned>& out) {
  out.push_back({{first - 50'000, true, {}}, tcp_flag::kSyn});
  out.push_back({{first - 49'000, false, {}}, tcp_flag::kSyn | tcp_flag::kAck});
  out.push_back({{first - 48'800, true, {}}, tcp_flag::kAck});
  out.push_back({{last + 100'000, true, {}}, tcp_flag::kFin | tcp_flag::kAck});
  out.push_back({{last + 101'000, false, {}}, tcp_flag::kFin | tcp_flag::kAck});
  out.push_back({{last + 101'200, true, {}}, tcp_flag::kAck});
}

}  // namespace

std::string write_tcp_session(std::vector<LanSegment> segments, const LanEndpoints& ends,
                              const std::string& path) {
  if (segments.empty()) return "nothing to capture";
  std::vector<Planned> plan;
  for (LanSegment& s : segments) {
    const std::uint8_t flags =
        s.payload.empty() ? tcp_flag::kAck : (tcp_flag::kAck | tcp_flag::kPsh);
    plan.push_back({std::move(s), flags});
  }
  std::stable_sort(plan.begin(), plan.end(),
                   [](const auto& a, const auto& b) { return a.segment.time < b.segment.time; });
  add_handshake(plan.front().segment.time, plan.back().segment.time, plan);
  std::stable_sort(plan.begin(), plan.end(),
                   [](const auto& a, const auto& b) { return a.segment.time < b.segment.time; });

  const Endpoint client = ipv4_endpoint(10, 0, 0, 1, ends.client_port);
  const Endpoint device = ipv4_endpoint(10, 0, 0, 3, ends.device_port);
  PcapWriter file;
  if (!file.open(path, DLT_EN10MB)) return file.error();
  // Each side's next byte; SYN and FIN count as one byte each.
  std::uint32_t next_seq[2] = {0x3C1E0000u, 0x0A5A0000u};  // client, device
  std::uint16_t ip_id[2] = {0x4000, 0x0100};
  for (const Planned& p : plan) {
    const int me = p.segment.from_client ? 0 : 1;
    TcpHeader h;
    h.window = me == 0 ? 64240 : 5840;  // the stick's and gateway's small embedded stacks
    h.seq = next_seq[me];
    h.flags = p.flags;
    h.ack = (p.flags & tcp_flag::kAck) ? next_seq[1 - me] : 0;
    h.ip_id = ip_id[me]++;
    const Route route = p.segment.from_client ? Route{client, device, kClientMac, kDeviceMac}
                                              : Route{device, client, kDeviceMac, kClientMac};
    file.write(p.segment.time, tcp_packet(LinkLayer::Ethernet, route, h, p.segment.payload));
    next_seq[me] += static_cast<std::uint32_t>(p.segment.payload.size());
    if (p.flags & (tcp_flag::kSyn | tcp_flag::kFin)) next_seq[me] += 1;
  }
  return file.close() ? std::string{} : file.error();
}

}  // namespace pvtap::sim
