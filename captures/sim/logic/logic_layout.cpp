#include "logic/logic_layout.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "sim_random.h"

namespace pvtap::sim {
namespace {

constexpr double kLeadIn = 20'000.0;  // idle line before the first frame and after the last
// A driver switching glitches only where the line is quiet this many characters either side,
// so that the glitch cannot touch the neighbouring frames' t3.5.
constexpr double kQuietForGlitch = 6.0;

bool clean_frame(const BusEvent& e) {
  return e.kind == BusEvent::Kind::Frame && e.check_ok && e.fault.empty();
}

// The events that carry the planted violations: `count` good replies straight after their
// request, and as many good requests of 4 bytes or more, spread over the session.
std::vector<std::string> plan_violations(const BusTimeline& t, unsigned count) {
  std::vector<std::string> plan(t.events.size());
  std::vector<std::size_t> replies, requests;
  for (std::size_t i = 1; i < t.events.size(); ++i) {
    const BusEvent& e = t.events[i];
    if (clean_frame(e) && e.role == Role::Response && t.events[i - 1].role == Role::Request &&
        clean_frame(t.events[i - 1]))
      replies.push_back(i);
    if (clean_frame(e) && e.role == Role::Request && e.bytes.size() >= 4) requests.push_back(i);
  }
  for (unsigned k = 0; k < count; ++k) {
    if (k < replies.size())
      plan[replies[(2 * k + 1) * replies.size() / (2 * count)]] = "early_reply";
    if (k >= requests.size()) continue;
    std::string& p = plan[requests[(2 * k + 1) * requests.size() / (2 * count)]];
    if (p.empty()) p = "pause_in_frame";
  }
  return plan;
}

// Each talker's driver turnaround is a property of its hardware: one delay per talker.
double release_of(int talker, std::map<int, double>& releases, SimRandom& random) {
  const auto found = releases.find(talker);
  if (found != releases.end()) return found->second;
  const auto r =
      static_cast<double>(talker == 0 ? random.between(10, 40) : random.between(20, 150));
  releases[talker] = r;
  return r;
}

class Layout {
 public:
  Layout(BusTimeline& t, const LogicOptions& o, unsigned baud, std::uint64_t seed)
      : t_(t), o_(o), random_(seed ^ 0x5EED10C1Cull) {
    out_.bit = 1e6 / baud * (1.0 + o.clock_deviation_pct / 100.0);
    char_ = out_.bit * o.format.bits_per_char();
  }

  LogicLayout run() {
    if (t_.events.empty()) return out_;
    out_.origin = t_.events.front().start - static_cast<Micros>(kLeadIn);
    const auto plan = plan_violations(t_, o_.violations);
    std::vector<double> old_gap_after(t_.events.size(), 1e12);
    for (std::size_t i = 0; i + 1 < t_.events.size(); ++i)
      old_gap_after[i] = static_cast<double>(t_.events[i + 1].start - t_.events[i].end);
    double prev_end = kLeadIn, prev_old_end = kLeadIn;
    for (std::size_t i = 0; i < t_.events.size(); ++i) {
      BusEvent& e = t_.events[i];
      const double old_start = static_cast<double>(e.start - out_.origin);
      const double gap = plan[i] == "early_reply" ? 2.5 * char_ : old_start - prev_old_end;
      prev_old_end = static_cast<double>(e.end - out_.origin);
      const bool quiet_after =
          i + 1 == t_.events.size() ||
          (plan[i + 1] != "early_reply" && old_gap_after[i] > (kQuietForGlitch + 1) * char_);
      prev_end = put_event(e, prev_end + gap, plan[i], gap > kQuietForGlitch * char_, quiet_after);
      shifts_.emplace_back(old_start, prev_end - prev_old_end);
      if (e.role == Role::Response && i > 0 && e.kind == BusEvent::Kind::Frame)
        e.latency = e.start - t_.events[i - 1].end;
    }
    out_.end = prev_end + kLeadIn;
    move_truth_times();
    return out_;
  }

 private:
  // Places one event from `start`; returns where its last stop bit ends.
  double put_event(BusEvent& e, double start, const std::string& violation, bool quiet_before,
                   bool quiet_after) {
    const bool master = e.role == Role::Request;
    double t = start;
    for (std::size_t j = 0; j < e.bytes.size(); ++j) {
      out_.characters.push_back({t, e.bytes[j], master});
      t += char_;
      if (violation == "pause_in_frame" && j == 1) t += 2.0 * char_;
    }
    if (!violation.empty()) out_.violations.push_back({start, violation, e.station});
    e.start = out_.origin + std::llround(start);
    e.end = out_.origin + std::llround(t);
    if (e.kind == BusEvent::Kind::Frame) {
      drive(master ? 0 : e.station, start, t, quiet_before, quiet_after && violation.empty());
    } else if (o_.undriven_space) {
      // Noise comes from a driver too: without one, nothing would lift the line to show it.
      hold_line(start - out_.bit * (1.0 + random_.unit()), t + out_.bit * random_.unit());
    }
    return t;
  }

  // --undriven space: the line driven from `on` to `off`, with its switch-on pulse.
  void hold_line(double on, double off) {
    const double spike_at = on + out_.bit * (0.05 + 0.15 * random_.unit());
    out_.driven.push_back({on, off, spike_at, out_.bit * (0.1 + 0.25 * random_.unit())});
  }

  // The talker's driver around its frame, and the glitches its switching makes.
  void drive(int talker, double first, double last, bool quiet_before, bool quiet_after) {
    // Without a failsafe bias the driver comes on a bit earlier: its switch-on pulse settles
    // half a bit before the first start bit at the latest.
    const double lead = o_.undriven_space ? 1.0 : 0.5;
    DriverWindow w{first - out_.bit * (lead + random_.unit()), 0, 0, talker};
    w.release = release_of(talker, releases_, random_);
    if (o_.truncate_last_byte && talker != 0 && (first_station_ < 0 || first_station_ == talker)) {
      first_station_ = talker;
      w.release = -0.5 * out_.bit;
    }
    w.off = last + w.release;
    if (o_.undriven_space) {
      // The line's own switching, at every turn, in place of the glitch bytes.
      hold_line(w.on, w.off);
      out_.drivers.push_back(w);
      return;
    }
    const unsigned bits = o_.format.bits_per_char();
    if (quiet_before && random_.percent(o_.glitch_pct)) {
      // Switching on: the line in space for a whole character, stop bit included (a 0x00
      // with a framing error), then idle for a bit or two before the frame.
      const double at = first - out_.bit * (bits + 1.0 + random_.unit());
      out_.glitches.push_back({at, static_cast<double>(bits), 0x00, true, talker});
      w.on = at;
    }
    if (quiet_after && w.release > 0 && random_.percent(o_.glitch_pct)) {
      // Switching off: a start bit, or a start bit and a 0 bit, as the line floats back.
      const bool fe = random_.percent(50);
      out_.glitches.push_back(
          {w.off, fe ? 2.0 : 1.0, std::uint8_t(fe ? 0xFE : 0xFF), false, talker});
    }
    out_.drivers.push_back(w);
  }

  // Old event start (from the origin) to the shift every time after it moved by.
  Micros moved(Micros t) const {
    const double rel = static_cast<double>(t - out_.origin);
    double shift = 0;
    for (const auto& [from, by] : shifts_) {
      if (from > rel) break;
      shift = by;
    }
    return t + std::llround(shift);
  }

  void move_truth_times() {
    for (auto* list : {&t_.timeouts, &t_.unanswered_damaged_requests, &t_.unanswered_at_end})
      for (TimeoutTruth& r : *list) {
        r.request_start = moved(r.request_start);
        r.request_end = moved(r.request_end);
      }
    for (FaultTruth& f : t_.faults) f.time = moved(f.time);
  }

  BusTimeline& t_;
  const LogicOptions& o_;
  SimRandom random_;
  LogicLayout out_;
  double char_ = 0;
  std::map<int, double> releases_;
  int first_station_ = -1;
  std::vector<std::pair<double, double>> shifts_;
};

}  // namespace

LogicLayout lay_out_logic(BusTimeline& timeline, const LogicOptions& options, unsigned baud,
                          std::uint64_t seed) {
  return Layout(timeline, options, baud, seed).run();
}

}  // namespace pvtap::sim
