#include "lan/mbap_session.h"

#include <algorithm>
#include <sstream>

#include "outputs/json_text.h"
#include "sim_random.h"

namespace pvtap::sim {
namespace {

constexpr Micros kMs = 1000;
constexpr std::uint8_t kGatewayTargetFailed = 0x0B;

struct MbapCounts {
  std::uint64_t adus = 0, requests = 0, responses = 0, gateway_exceptions = 0, pipelined = 0,
                lying_lengths = 0, carrier_bytes = 0, pdu_bytes = 0;
};

// One ADU: the MBAP header before unit id and PDU.
std::vector<std::uint8_t> adu(std::uint16_t transaction, std::span<const std::uint8_t> unit_pdu,
                              std::size_t length_field) {
  std::vector<std::uint8_t> out;
  out.reserve(6 + unit_pdu.size());
  for (const std::size_t v : {std::size_t{transaction}, std::size_t{0}, length_field}) {
    out.push_back(static_cast<std::uint8_t>(v >> 8));
    out.push_back(static_cast<std::uint8_t>(v));
  }
  out.insert(out.end(), unit_pdu.begin(), unit_pdu.end());
  return out;
}

class MbapPlanner {
 public:
  MbapPlanner(const BusTimeline& timeline, const MbapOptions& options, std::uint64_t seed)
      : timeline_(timeline), options_(options), random_(seed ^ 0x3B0A9ull) {
    out_.ends = {50502, 502};
    transaction_ = static_cast<std::uint16_t>(random_.between(1, 0xFFFF));
  }
  // Sends exchange x's request (at `at`) and its answer; returns when the answer left.
  Micros exchange(const LanExchange& x, Micros at);
  bool pipeline() { return random_.percent(options_.faults["pipeline"]); }
  Micros lead() { return random_.between(1, 3) * kMs; }
  LanCapture finish();
  void count_pipelined() { ++n_.pipelined; }

 private:
  void send(Micros at, bool from_client, std::vector<std::uint8_t> bytes, std::string truth);
  std::string truth(Micros at, bool from_client, std::uint16_t transaction,
                    std::span<const std::uint8_t> unit_pdu, std::size_t length_field) const;
  bool is_timeout(const BusEvent& request) const;

  const BusTimeline& timeline_;
  MbapOptions options_;
  SimRandom random_;
  LanCapture out_;
  MbapCounts n_;
  std::uint16_t transaction_ = 0;
  std::vector<std::pair<Micros, std::string>> frames_;  // truth, in call order
};

std::string MbapPlanner::truth(Micros at, bool from_client, std::uint16_t transaction,
                               std::span<const std::uint8_t> unit_pdu,
                               std::size_t length_field) const {
  std::ostringstream o;
  o << "{\"ts\":" << seconds(at) << ",\"from\":\"" << (from_client ? "client" : "gateway")
    << "\",\"transaction\":" << transaction << ",\"unit\":" << int{unit_pdu[0]}
    << ",\"function\":" << int{unit_pdu[1]} << ",\"length\":" << unit_pdu.size()
    << ",\"length_field\":" << length_field;
  return o.str();
}

void MbapPlanner::send(Micros at, bool from_client, std::vector<std::uint8_t> bytes,
                       std::string truth) {
  frames_.push_back({at, truth + "}"});
  ++n_.adus;
  n_.carrier_bytes += 6;  // transaction, protocol, length; the unit id is the station
  n_.pdu_bytes += bytes.size() - 6;
  out_.segments.push_back({at, from_client, std::move(bytes)});
  out_.segments.push_back({at + (from_client ? 300 : 200), !from_client, {}});
}

bool MbapPlanner::is_timeout(const BusEvent& request) const {
  for (const TimeoutTruth& t : timeline_.timeouts)
    if (t.request_start == request.start) return true;
  return false;
}

Micros MbapPlanner::exchange(const LanExchange& x, Micros at) {
  const BusEvent& req = timeline_.events[x.request];
  const std::uint16_t tid = transaction_++;
  // Unit id and PDU: the RTU frame without its CRC.
  const std::span<const std::uint8_t> unit_pdu(req.bytes.data(), req.bytes.size() - 2);
  ++n_.requests;
  send(at, true, adu(tid, unit_pdu, unit_pdu.size()),
       truth(at, true, tid, unit_pdu, unit_pdu.size()) + ",\"event\":" + std::to_string(x.request));
  if (x.reply) {
    const BusEvent& rep = timeline_.events[*x.reply];
    const Micros t = rep.end + random_.between(1, 4) * kMs;
    const std::span<const std::uint8_t> reply_pdu(rep.bytes.data(), rep.bytes.size() - 2);
    std::size_t field = reply_pdu.size();
    if (random_.percent(options_.faults["lying_length"])) {
      field += static_cast<std::size_t>(random_.between(1, 3));
      ++n_.lying_lengths;
    }
    ++n_.responses;
    send(t, false, adu(tid, reply_pdu, field),
         truth(t, false, tid, reply_pdu, field) + ",\"event\":" + std::to_string(*x.reply));
    return t;
  }
  if (!is_timeout(req)) return req.end;  // still waiting when the capture ends
  // The gateway gave up on the bus: exception 0x0B, gateway target device failed to respond.
  const Micros t =
      req.end + static_cast<Micros>(options_.bus_timeout_s * 1e6) + random_.between(1, 5) * kMs;
  const std::vector<std::uint8_t> exception{
      req.bytes[0], static_cast<std::uint8_t>(req.bytes[1] | 0x80), kGatewayTargetFailed};
  ++n_.gateway_exceptions;
  ++n_.responses;
  send(t, false, adu(tid, exception, exception.size()),
       truth(t, false, tid, exception, exception.size()) + ",\"gateway_exception\":true");
  return t;
}

LanCapture MbapPlanner::finish() {
  // A pipelined request leaves before the reply planned ahead of it: the truth is in time order.
  std::stable_sort(frames_.begin(), frames_.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  for (auto& f : frames_) out_.truth.frames.push_back(std::move(f.second));
  out_.truth.carrier = "mbap";
  out_.truth.counts = {{"port", 502},
                       {"adus", n_.adus},
                       {"requests", n_.requests},
                       {"responses", n_.responses},
                       {"gateway_exceptions", n_.gateway_exceptions},
                       {"pipelined_requests", n_.pipelined},
                       {"lying_lengths", n_.lying_lengths},
                       {"carrier_bytes", n_.carrier_bytes},
                       {"pdu_bytes", n_.pdu_bytes}};
  return std::move(out_);
}

}  // namespace

const std::vector<std::string>& mbap_fault_kinds() {
  static const std::vector<std::string> kinds{"pipeline", "lying_length"};
  return kinds;
}

LanCapture plan_mbap_session(const BusTimeline& timeline, const MbapOptions& options,
                             std::uint64_t seed) {
  MbapPlanner planner(timeline, options, seed);
  const std::vector<LanExchange> exchanges = lan_exchanges(timeline);
  Micros last_sent = 0;  // the client's previous request
  bool previous_pipelined = false;
  for (std::size_t i = 0; i < exchanges.size(); ++i) {
    const Micros bus_start = timeline.events[exchanges[i].request].start;
    Micros at = bus_start - planner.lead();
    // Pipelined: sent just after the request before it, and queued by the gateway until the
    // bus is free (one request in waiting at most, as gateways allow).
    if (i > 0 && !previous_pipelined && bus_start - last_sent < 500 * kMs && planner.pipeline()) {
      at = last_sent + planner.lead();
      planner.count_pipelined();
      previous_pipelined = true;
    } else {
      previous_pipelined = false;
    }
    last_sent = at;
    planner.exchange(exchanges[i], at);
  }
  return planner.finish();
}

}  // namespace pvtap::sim
