#include "lan/v5_session.h"

#include <algorithm>
#include <cstdio>
#include <set>
#include <sstream>

#include "lan/v5_frame.h"
#include "outputs/json_text.h"
#include "sim_random.h"

namespace pvtap::sim {
namespace {

constexpr Micros kMs = 1000;
constexpr std::size_t kQuirkBytes = 2;
// The codes a stick answers in place of an RTU frame: no reply came from the bus, and a
// request addressed to a serial it does not have.
constexpr std::uint8_t kNoReplyCode = 0x05;
constexpr std::uint8_t kWrongSerialCode = 0x06;

// V5Counts: the carrier's totals in the ground truth.
struct V5Counts {
  std::uint64_t frames = 0, requests = 0, responses = 0, heartbeats = 0, data_reports = 0,
                client_answers = 0, carrier_bytes = 0, rtu_bytes = 0, quirk_bytes = 0,
                bad_checksums = 0, dropped_replies = 0, split_frames = 0, shared_segments = 0,
                stick_codes = 0, stick_timeouts = 0, refused_requests = 0,
                replies_after_next_request = 0;
};

// The kinds of --v5-faults whose counts the truth names only when one of them is asked for
// (the samples written before them keep their bytes).
bool stick_behaviour(const CarrierFaults& f) {
  return f["stick_code"] + f["wrong_serial"] + f["late"] + f["beat_first"] > 0;
}

// A fault drawn only when asked for: a draw of a kind at 0 % would move every later draw.
bool happens(SimRandom& random, const CarrierFaults& faults, std::string_view kind) {
  return faults[kind] > 0 && random.percent(faults[kind]);
}

// V5Item: what the client sends in time order: an exchange of the timeline, or a request it
// addressed to a wrong serial (its RTU frame never reached the bus).
struct V5Item {
  Micros bus_start = 0;  // of the request: the order of the items
  // When the client sent it; an exchange's is drawn at its turn (or when the one before
  // looks ahead), in the order the samples were written with.
  std::optional<Micros> request_at;
  std::optional<LanExchange> exchange;
  std::vector<std::uint8_t> refused_rtu;
};

// One V5 frame as it goes out, and what the truth says of it.
struct OutFrame {
  std::vector<std::uint8_t> bytes;
  std::optional<std::size_t> event;  // the RTU frame it carries
  std::size_t rtu = 0, quirk = 0;
  bool bad_checksum = false;
  std::optional<std::uint8_t> stick_code;  // a response with the stick's code, no RTU frame
  bool refused = false;                    // a request the stick refused (code 06)
  std::optional<Micros> late_since;        // a late reply: when its request was sent
};

class V5Planner {
 public:
  V5Planner(const BusTimeline& timeline, const V5Options& options, Micros start, std::uint64_t seed)
      : timeline_(timeline), options_(options), start_(start), random_(seed ^ 0x5A1A5A1ull) {
    out_.ends = {51234, 8899};
    client_seq_ = static_cast<std::uint8_t>(random_.between(1, 255));
  }

  void exchange(const LanExchange& x, Micros request_at, std::optional<Micros> next_request_at,
                bool code_05);
  void refused(const std::vector<std::uint8_t>& rtu, Micros request_at);
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
  OutFrame code_frame(std::uint8_t code, std::uint8_t seq0, Micros at);
  std::uint8_t send_request(std::span<const std::uint8_t> rtu, std::optional<std::size_t> event,
                            std::uint32_t serial, Micros at);
  bool late_window(Micros request_at, Micros reply_at, std::optional<Micros> next_request_at) const;

  const BusTimeline& timeline_;
  V5Options options_;
  Micros start_;
  SimRandom random_;
  LanCapture out_;
  V5Counts n_;
  std::uint8_t client_seq_ = 0, stick_seq_ = 0, stick_own_ = 0;
  Micros last_heartbeat_ = 0, last_data_report_ = 0;
  std::optional<OutFrame> late_;  // a reply the stick holds until the client's next request
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
  if (f.stick_code) o << ",\"stick_code\":\"" << hex(std::span(&*f.stick_code, 1)) << "\"";
  if (f.refused) o << ",\"refused\":true";
  if (f.late_since)
    o << ",\"late\":true,\"latency_ms\":" << number(static_cast<double>(at - *f.late_since) / 1e3);
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

// Sends the client's request and, after it, a reply the stick held back; returns its sequence
// byte 0.
std::uint8_t V5Planner::send_request(std::span<const std::uint8_t> rtu,
                                     std::optional<std::size_t> event, std::uint32_t serial,
                                     Micros at) {
  OutFrame r;
  r.event = event;
  r.rtu = rtu.size();
  r.refused = serial != options_.logger_serial;
  const std::uint8_t seq0 = client_seq_++;
  r.bytes = v5_frame(v5_control::kRequest, seq0, 0x00, serial, solarman_v5::request_payload(rtu));
  ++n_.requests;
  send(at, true, r);
  if (late_) {
    send_reply(*late_, at + 2 * kMs, false);  // after the stick acknowledged the request
    ++n_.replies_after_next_request;
    late_.reset();
  }
  return seq0;
}

// A response that carries the stick's code (two bytes: the code, 0) in place of an RTU frame.
OutFrame V5Planner::code_frame(std::uint8_t code, std::uint8_t seq0, Micros at) {
  const std::uint8_t body[2] = {code, 0x00};
  OutFrame f;
  f.stick_code = code;
  f.bytes = v5_frame(v5_control::kResponse, seq0, ++stick_seq_, options_.logger_serial,
                     v5_response_payload(body, clock(at), 0));
  ++n_.stick_codes;
  return f;
}

// Whether a reply may be held until after the client's next request: it must still come
// within the client's wait.
bool V5Planner::late_window(Micros request_at, Micros reply_at,
                            std::optional<Micros> next_request_at) const {
  if (!next_request_at || *next_request_at <= reply_at || late_) return false;
  const auto wait = static_cast<Micros>(options_.client_timeout_s * 1e6);
  return *next_request_at + 50 * kMs - request_at < wait;
}

void V5Planner::exchange(const LanExchange& x, Micros request_at,
                         std::optional<Micros> next_request_at, bool code_05) {
  const BusEvent& req = timeline_.events[x.request];
  const std::uint8_t seq0 = send_request(req.bytes, x.request, options_.logger_serial, request_at);
  if (!x.reply) {
    if (!code_05) return;
    // The stick waited for the bus in vain, then says so within the client's wait.
    const auto wait = static_cast<Micros>(options_.client_timeout_s * 1e6);
    const Micros at = req.end + random_.between(30, 70) * wait / 100;
    ++n_.stick_timeouts;
    send(at, false, code_frame(kNoReplyCode, seq0, at));
    return;
  }
  const Micros at = timeline_.events[*x.reply].end + random_.between(2, 6) * kMs;
  const bool can_be_late = late_window(request_at, at, next_request_at);
  const bool beat_first = can_be_late && happens(random_, options_.faults, "beat_first");
  if (beat_first || (can_be_late && happens(random_, options_.faults, "late"))) {
    if (beat_first) {
      const OutFrame s = stick_frame(false, at);
      send(at, false, s);
      answer(s, at + 600);
    }
    late_ = reply_frame(*x.reply, seq0, at);
    late_->late_since = request_at;
    return;
  }
  const bool merged = random_.percent(options_.faults["merge"]);
  Micros done = send_reply(reply_frame(*x.reply, seq0, at), at, merged);
  if (const auto data_report = stick_frame_due(done)) {
    const Micros t = done + random_.between(1, 2) * kMs;
    const OutFrame s = stick_frame(*data_report, t);
    send(t, false, s);
    answer(s, t + 600);
  }
}

// A request to a serial the stick does not have: it refuses it with code 06 and its own
// serial, and nothing reaches the bus.
void V5Planner::refused(const std::vector<std::uint8_t>& rtu, Micros request_at) {
  const std::uint8_t seq0 = send_request(rtu, std::nullopt, options_.wrong_serial, request_at);
  const Micros at = request_at + random_.between(5, 20) * kMs;
  ++n_.refused_requests;
  send(at, false, code_frame(kWrongSerialCode, seq0, at));
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
  if (stick_behaviour(options_.faults)) {
    out_.truth.counts.insert(out_.truth.counts.end(),
                             {{"stick_codes", n_.stick_codes},
                              {"stick_timeouts", n_.stick_timeouts},
                              {"refused_requests", n_.refused_requests},
                              {"replies_after_next_request", n_.replies_after_next_request}});
  }
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

// The exchanges whose request the client addressed to a wrong serial: clean ones (a good
// request, a clean reply), taken out of the timeline with their reply, since the stick
// refused the request and nothing reached the bus.
std::vector<V5Item> refuse_exchanges(BusTimeline& timeline, const CarrierFaults& faults,
                                     SimRandom& random) {
  std::vector<V5Item> out;
  if (faults["wrong_serial"] == 0) return out;
  std::vector<bool> gone(timeline.events.size(), false);
  for (const LanExchange& x : lan_exchanges(timeline)) {
    const BusEvent& req = timeline.events[x.request];
    if (!x.reply || !req.check_ok || !timeline.events[*x.reply].fault.empty()) continue;
    if (!random.percent(faults["wrong_serial"])) continue;
    out.push_back({req.start, req.start - random.between(2, 4) * kMs, std::nullopt, req.bytes});
    gone[x.request] = gone[*x.reply] = true;
  }
  std::vector<BusEvent> kept;
  for (std::size_t i = 0; i < timeline.events.size(); ++i)
    if (!gone[i]) kept.push_back(std::move(timeline.events[i]));
  timeline.events = std::move(kept);
  return out;
}

// The requests the bus left unanswered that the stick answers with code 05 (by their start):
// in the truth they stay timeouts, with the stick's reason.
std::set<Micros> no_reply_codes(BusTimeline& timeline, const CarrierFaults& faults,
                                SimRandom& random) {
  std::set<Micros> out;
  if (faults["stick_code"] == 0) return out;
  for (TimeoutTruth& t : timeline.timeouts) {
    if (!random.percent(faults["stick_code"])) continue;
    t.reason = "the stick answered code 05";
    out.insert(t.request_start);
  }
  return out;
}

}  // namespace

const std::vector<std::string>& v5_fault_kinds() {
  static const std::vector<std::string> kinds{"quirk",        "drop",  "bad_checksum",
                                              "split",        "merge", "stick_code",
                                              "wrong_serial", "late",  "beat_first"};
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
  SimRandom stick(seed ^ 0x57C0DEull);
  const std::vector<V5Item> refusals = refuse_exchanges(timeline, options.faults, stick);
  const std::set<Micros> code_05 = no_reply_codes(timeline, options.faults, stick);
  std::vector<V5Item> items = refusals;
  for (const LanExchange& x : lan_exchanges(timeline))
    items.push_back({timeline.events[x.request].start, std::nullopt, x, {}});
  std::stable_sort(items.begin(), items.end(),
                   [](const V5Item& a, const V5Item& b) { return a.bus_start < b.bus_start; });
  V5Planner planner(timeline, options, start, seed);
  const auto sent_at = [&](V5Item& item) {
    if (!item.request_at) item.request_at = planner.request_time(item.exchange->request);
    return *item.request_at;
  };
  const bool look_ahead = options.faults["late"] + options.faults["beat_first"] > 0;
  for (std::size_t i = 0; i < items.size(); ++i) {
    V5Item& item = items[i];
    if (!item.exchange) {
      planner.refused(item.refused_rtu, *item.request_at);
      continue;
    }
    const Micros at = sent_at(item);
    std::optional<Micros> next;
    if (look_ahead && i + 1 < items.size()) next = sent_at(items[i + 1]);
    planner.exchange(*item.exchange, at, next, code_05.contains(item.bus_start));
  }
  return planner.finish(dropped.size());
}

}  // namespace pvtap::sim
