#include <pcap/pcap.h>

#include <algorithm>

#include "outputs/bus_bytes.h"
#include "outputs/capture_outputs.h"
#include "pvtap/pcap/packet_builder.h"
#include "pvtap/pcap/pcap_writer.h"
#include "sim_random.h"

namespace pvtap::sim {
namespace {

const Endpoint kMaster = ipv4_endpoint(10, 0, 0, 1, 50123);
const Endpoint kGateway = ipv4_endpoint(10, 0, 0, 2, 4001);
const MacAddress kMasterMac{0x02, 0, 0, 0, 0, 0x01};
const MacAddress kGatewayMac{0x02, 0, 0, 0, 0, 0x02};

// PlannedSegment: one TCP segment before sequence numbers are known.
struct PlannedSegment {
  Micros time = 0;
  bool from_master = false;
  std::uint8_t flags = tcp_flag::kAck;
  std::vector<std::uint8_t> payload;
};

// The master writes each request in one piece; it reaches the bus half a millisecond later.
constexpr Micros kRequestLead = 500;
// The master's ACK of a gateway segment.
constexpr Micros kAckDelay = 150;

void plan_requests(const BusTimeline& timeline, std::vector<PlannedSegment>& out) {
  for (const BusEvent& e : timeline.events) {
    if (e.role != Role::Request) continue;
    out.push_back({e.start - kRequestLead, true, tcp_flag::kAck | tcp_flag::kPsh, e.bytes});
    out.push_back({e.start - 300, false, tcp_flag::kAck, {}});
  }
}

// When the master sends each request, in time order.
std::vector<Micros> request_times(const BusTimeline& timeline) {
  std::vector<Micros> out;
  for (const BusEvent& e : timeline.events)
    if (e.role == Role::Request) out.push_back(e.start - kRequestLead);
  return out;
}

// The gateway sends what the bus gave it whenever its packing timer, restarted at random
// lengths, runs out: frames end up split over segments and merged into one.
void plan_replies(const BusTimeline& timeline, SimRandom& random,
                  std::vector<PlannedSegment>& out) {
  const std::vector<Micros> polls = request_times(timeline);
  auto next_poll = polls.begin();
  std::vector<std::uint8_t> pending;
  Micros deadline = 0;
  auto flush = [&] {
    out.push_back({deadline, false, tcp_flag::kAck | tcp_flag::kPsh, pending});
    out.push_back({deadline + kAckDelay, true, tcp_flag::kAck, {}});
    pending.clear();
  };
  for (const TimedByte& b : bus_bytes(timeline)) {
    if (b.side != Role::Response) continue;
    if (!pending.empty() && b.time > deadline) flush();
    if (pending.empty()) {
      // At most 15 ms, and never past the next request: the master has the whole reply
      // before it polls again, however soon it does.
      deadline = b.time + random.between(1'000, 15'000);
      while (next_poll != polls.end() && *next_poll <= b.time) ++next_poll;
      if (next_poll != polls.end())
        deadline = std::max(b.time, std::min(deadline, *next_poll - 2 * kAckDelay));
    }
    pending.push_back(b.value);
  }
  if (!pending.empty()) flush();
}

void plan_handshake(Micros first, Micros last, std::vector<PlannedSegment>& out) {
  out.push_back({first - 50'000, true, tcp_flag::kSyn, {}});
  out.push_back({first - 49'800, false, tcp_flag::kSyn | tcp_flag::kAck, {}});
  out.push_back({first - 49'600, true, tcp_flag::kAck, {}});
  out.push_back({last + 100'000, true, tcp_flag::kFin | tcp_flag::kAck, {}});
  out.push_back({last + 100'200, false, tcp_flag::kFin | tcp_flag::kAck, {}});
  out.push_back({last + 100'400, true, tcp_flag::kAck, {}});
}

}  // namespace

std::string write_gateway_capture(const BusTimeline& timeline, const std::string& path,
                                  std::uint64_t seed) {
  if (timeline.events.empty()) return "nothing to capture";
  SimRandom random(seed ^ 0x6A7E3A1ull);
  std::vector<PlannedSegment> plan;
  plan_requests(timeline, plan);
  plan_replies(timeline, random, plan);
  plan_handshake(timeline.events.front().start, timeline.events.back().end + 50'000, plan);
  std::stable_sort(plan.begin(), plan.end(),
                   [](const auto& a, const auto& b) { return a.time < b.time; });

  PcapWriter file;
  if (!file.open(path, DLT_EN10MB)) return file.error();
  // Sequence numbers: each side's next byte; SYN and FIN count as one byte each.
  std::uint32_t next_seq[2] = {0x1A2B3C00u, 0x5F000000u};  // master, gateway
  std::uint16_t ip_id[2] = {0x2000, 0x7000};
  for (const PlannedSegment& s : plan) {
    const int me = s.from_master ? 0 : 1;
    TcpHeader f;
    f.window = 64240;
    f.seq = next_seq[me];
    f.flags = s.flags;
    f.ack = (s.flags & tcp_flag::kAck) ? next_seq[1 - me] : 0;
    f.ip_id = ip_id[me]++;
    const Route route = s.from_master ? Route{kMaster, kGateway, kMasterMac, kGatewayMac}
                                      : Route{kGateway, kMaster, kGatewayMac, kMasterMac};
    file.write(s.time, tcp_packet(LinkLayer::Ethernet, route, f, s.payload));
    next_seq[me] += static_cast<std::uint32_t>(s.payload.size());
    if (s.flags & (tcp_flag::kSyn | tcp_flag::kFin)) next_seq[me] += 1;
  }
  return file.close() ? std::string{} : file.error();
}

}  // namespace pvtap::sim
