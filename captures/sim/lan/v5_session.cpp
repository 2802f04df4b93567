#include "lan/v5_session.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "lan/v5_frame.h"
#include "outputs/json_text.h"
#include "sim_random.h"

namespace pvtap::sim {
namespace {

constexpr Micros kMs = 1000;
constexpr std::size_t kQuirkBytes = 2;

// V5Counts: the carrier's totals in the ground truth.
struct V5Counts {
  std::uint64_t frames = 0, requests = 0, responses = 0, heartbeats = 0, data_reports = 0,
                client_answers = 0, carrier_bytes = 0, rtu_bytes = 0, quirk_bytes = 0,
                bad_checksums = 0, dropped_replies = 0, split_frames = 0, shared_segments = 0;
};

// One V5 frame as it goes out, and what the truth says of it.
struct OutFrame {
  std::vector<std::uint8_t> bytes;
  std::optional<std::size_t> event;  // the RTU frame it carries
  std::size_t rtu = 0, quirk = 0;
  bool bad_checksum = false;
};

class V5Planner {
 public:
  V5Planner(const BusTimeline& timeline, const V5Options& options, Micros start, std::uint64_t seed)
      : timeline_(timeline), options_(options), start_(start), random_(seed ^ 0x5A1A5A1ull) {
    out_.ends = {51234, 8899};
    client_seq_ = static_cast<std::uint8_t>(random_.between(1, 255));
  }

  void exchange(const LanExchange& x, Micros request_at);
  LanCapture finish(std::uint64_t dropped);
  Micros request_time(std::size_t event) { return timeline_.events[event].start - lead(); }

 private:
  Micros lead() { return random_.between(2, 4) * kMs; }
  V5Clock clock(Micros at) const;
  void send(Micros at, bool from_client, const OutFrame& f, std::size_t segments = 1,
            bool shared = false);
  void segment(Micros at, bool from_client, std::vector<std::uint8_t> bytes);
  OutFrame reply_frame(std::size_t event, std::uint8_t seq0, Micros at);
  OutFrame stick_frame(bool data_report, Micros at);
  Micros send_reply(const OutFrame& f, Micros at, bool merged);
  void answer(const OutFrame& stick, Micros at);
  std::optional<bool> stick_frame_due(Micros at);  // data report (true) or heartbeat
  void record(Micros at, bool from_client, const OutFrame& f, std::size_t segments, bool shared);

  const BusTimeline& timeline_;
  V5Options options_;
  Micros start_;
  SimRandom random_;
  LanCapture out_;
  V5Counts n_;
  std::uint8_t client_seq_ = 0, stick_seq_ = 0, stick_own_ = 0;
  Micros last_heartbeat_ = 0, last_data_report_ = 0;
};

V5Clock V5Planner::clock(Micros at) const {
  const auto power_on = static_cast<std::uint32_t>(5 * 3600 + (at - start_) / 1'000'000);
  const auto unix_s = static_cast<std::uint32_t>(at / 1'000'000);
  return {40 * 86400 + power_on, power_on, unix_s - power_on};
}

void V5Planner::segment(Micros at, bool from_client, std::vector<std::uint8_t> bytes) {
  out_.segments.push_back({at, from_client, std::move(bytes)});
  // The other side acknowledges every data segment: the stick at once, the client too.
  out_.segments.push_back({at + (from_client ? 1500 : 200), !from_client, {}});
}

void V5Planner::record(Micros at, bool from_client, const OutFrame& f, std::size_t segments,
                       bool shared) {
  const auto control = static_cast<unsigned>(f.bytes[3] | (f.bytes[4] << 8));
  std::ostringstream o;
  char code[8];
  std::snprintf(code, sizeof code, "0x%04x", control);
  o << "{\"ts\":" << seconds(at) << ",\"from\":\"" << (from_client ? "client" : "stick")
    << "\",\"control\":\"" << code << "\",\"sequence\":\"" << hex(std::span(f.bytes).subspan(5, 2))
    << "\",\"length\":" << f.bytes.size() - solarman_v5::kOverhead << ",\"checksum\":\""
    << (f.bad_checksum ? "bad" : "ok") << "\"";
  if (f.event) o << ",\"event\":" << *f.event;
  if (f.quirk) o << ",\"quirk_bytes\":" << f.quirk;
  if (segments > 1) o << ",\"segments\":" << segments;
  if (shared) o << ",\"shared_segment\":true";
  o << "}";
  out_.truth.frames.push_back(o.str());
  ++n_.frames;
  n_.rtu_bytes += f.rtu;
  n_.quirk_bytes += f.quirk;
  n_.carrier_bytes += f.bytes.size() - f.rtu - f.quirk;
  n_.bad_checksums += f.bad_checksum ? 1 : 0;
  n_.split_frames += segments > 1 ? 1 : 0;
}

void V5Planner::send(Micros at, bool from_client, const OutFrame& f, std::size_t segments,
                     bool shared) {
  record(at, from_client, f, segments, shared);
  segment(at, from_client, f.bytes);
}

OutFrame V5Planner::reply_frame(std::size_t event, std::uint8_t seq0, Micros at) {
  const std::vector<std::uint8_t>& rtu = timeline_.events[event].bytes;
  OutFrame f;
  f.event = event;
  f.rtu = rtu.size();
  f.quirk = random_.percent(options_.faults["quirk"]) ? kQuirkBytes : 0;
  f.bytes = v5_frame(v5_control::kResponse, seq0, ++stick_seq_, options_.logger_serial,
                     v5_response_payload(rtu, clock(at), f.quirk));
  if (random_.percent(options_.faults["bad_checksum"])) {
    f.bad_checksum = true;
    f.bytes[f.bytes.size() - 2] += static_cast<std::uint8_t>(random_.between(1, 255));
  }
  return f;
}

OutFrame V5Planner::stick_frame(bool data_report, Micros at) {
  std::vector<std::uint8_t> payload{0x00};  // a heartbeat's one byte
  if (data_report) {
    // Frame type 0x01, a sensor type, the times, then the stick's own record of the inverter.
    const V5Clock c = clock(at);
    payload = {0x01, 0x00, 0x02};
    for (std::uint32_t v : {c.total_working_s, c.power_on_s, c.offset_s})
      for (int i = 0; i < 4; ++i) payload.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
    for (int i = 0; i < 48; ++i) payload.push_back(static_cast<std::uint8_t>(random_.next()));
  }
  OutFrame f;
  f.bytes = v5_frame(data_report ? v5_control::kDataReport : v5_control::kHeartbeat, ++stick_own_,
                     ++stick_seq_, options_.logger_serial, payload);
  ++(data_report ? n_.data_reports : n_.heartbeats);
  return f;
}

// The client answers a stick frame with the same sequence, as pysolarmanv5 does.
void V5Planner::answer(const OutFrame& stick, Micros at) {
  const bool data_report = stick.bytes[4] == 0x42;
  OutFrame f;
  f.bytes = v5_frame(
      static_cast<std::uint16_t>((data_report ? v5_control::kDataReport : v5_control::kHeartbeat) -
                                 v5_control::kReplyOffset),
      stick.bytes[5], stick.bytes[6], options_.logger_serial,
      v5_answer_payload(data_report ? 0x01 : 0x00, static_cast<std::uint32_t>(at / 1'000'000)));
  ++n_.client_answers;
  send(at, true, f);
}

std::optional<bool> V5Planner::stick_frame_due(Micros at) {
  const auto due = [&](double period_s, Micros& last) {
    if (period_s <= 0 || at - last < static_cast<Micros>(period_s * 1e6)) return false;
    last = at;
    return true;
  };
  if (last_heartbeat_ == 0) last_heartbeat_ = last_data_report_ = at;
  if (due(options_.data_report_s, last_data_report_)) return true;
  if (due(options_.heartbeat_s, last_heartbeat_)) return false;
  return std::nullopt;
}

// Sends a reply whole, split over two segments, or behind a heartbeat in one; returns when
// its last byte left.
Micros V5Planner::send_reply(const OutFrame& f, Micros at, bool merged) {
  ++n_.responses;
  if (merged) {
    const OutFrame beat = stick_frame(false, at);
    record(at, false, beat, 1, true);
    record(at, false, f, 1, true);
    std::vector<std::uint8_t> both = beat.bytes;
    both.insert(both.end(), f.bytes.begin(), f.bytes.end());
    segment(at, false, std::move(both));
    ++n_.shared_segments;
    answer(beat, at + 600);
    return at + 600;
  }
  if (!random_.percent(options_.faults["split"])) {
    send(at, false, f);
    return at;
  }
  const auto size = static_cast<std::int64_t>(f.bytes.size());
  const std::ptrdiff_t cut = random_.between(1, size - 1);
  const Micros second = at + random_.between(1, 4) * kMs;
  record(second, false, f, 2, false);
  segment(at, false, {f.bytes.begin(), f.bytes.begin() + cut});
  segment(second, false, {f.bytes.begin() + cut, f.bytes.end()});
  return second;
}

void V5Planner::exchange(const LanExchange& x, Micros request_at) {
  const BusEvent& req = timeline_.events[x.request];
  OutFrame r;
  r.event = x.request;
  r.rtu = req.bytes.size();
  const std::uint8_t seq0 = client_seq_++;
  r.bytes = v5_frame(v5_control::kRequest, seq0, 0x00, options_.logger_serial,
                     solarman_v5::request_payload(req.bytes));
  ++n_.requests;
  send(request_at, true, r);
  if (!x.reply) return;
  const Micros at = timeline_.events[*x.reply].end + random_.between(2, 6) * kMs;
  const bool merged = random_.percent(options_.faults["merge"]);
  Micros done = send_reply(reply_frame(*x.reply, seq0, at), at, merged);
  if (const auto data_report = stick_frame_due(done)) {
    const Micros t = done + random_.between(1, 2) * kMs;
    const OutFrame s = stick_frame(*data_report, t);
    send(t, false, s);
    answer(s, t + 600);
  }
}

LanCapture V5Planner::finish(std::uint64_t dropped) {
  n_.dropped_replies = dropped;
  out_.truth.carrier = "v5";
  out_.truth.counts = {{"logger_serial", options_.logger_serial},
                       {"port", 8899},
                       {"frames", n_.frames},
                       {"requests", n_.requests},
                       {"responses", n_.responses},
                       {"stick_frames", n_.heartbeats + n_.data_reports},
                       {"heartbeats", n_.heartbeats},
                       {"data_reports", n_.data_reports},
                       {"client_answers", n_.client_answers},
                       {"carrier_bytes", n_.carrier_bytes},
                       {"rtu_bytes", n_.rtu_bytes},
                       {"quirk_bytes", n_.quirk_bytes},
                       {"bad_checksums", n_.bad_checksums},
                       {"dropped_replies", n_.dropped_replies},
                       {"split_frames", n_.split_frames},
                       {"shared_segments", n_.shared_segments}};
  return std::move(out_);
}

// The replies the stick drops, chosen before anything else so that the rest of the plan sees
// the timeline the client saw.
std::vector<std::size_t> dropped_replies(const BusTimeline& timeline, unsigned percent,
                                         SimRandom& random) {
  std::vector<std::size_t> out;
  for (const LanExchange& x : lan_exchanges(timeline))
    if (x.reply && random.percent(percent)) out.push_back(*x.reply);
  return out;
}

}  // namespace

const std::vector<std::string>& v5_fault_kinds() {
  static const std::vector<std::string> kinds{"quirk", "drop", "bad_checksum", "split", "merge"};
  return kinds;
}

LanCapture plan_v5_session(BusTimeline& timeline, const V5Options& options, Micros start,
                           std::uint64_t seed) {
  SimRandom drops(seed ^ 0xD209ull);
  const std::vector<std::size_t> dropped = dropped_replies(timeline, options.faults["drop"], drops);
  for (std::size_t r : dropped) {
    while (timeline.events[r].role != Role::Request) --r;  // a reply follows its request
    const BusEvent& request = timeline.events[r];
    timeline.faults.push_back({request.end, request.station, "stick_drop"});
  }
  std::stable_sort(timeline.faults.begin(), timeline.faults.end(),
                   [](const auto& a, const auto& b) { return a.time < b.time; });
  drop_replies(timeline, dropped);
  V5Planner planner(timeline, options, start, seed);
  for (const LanExchange& x : lan_exchanges(timeline))
    planner.exchange(x, planner.request_time(x.request));
  return planner.finish(dropped.size());
}

}  // namespace pvtap::sim
