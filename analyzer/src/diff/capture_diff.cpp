#include "diff/capture_diff.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string_view>
#include <utility>

#include "formatting/number_text.h"
#include "report/poll_block_text.h"

namespace pvtap::analyzer {
namespace {

std::string bus_label(const BusFindings& bus) {
  return bus.name.empty() ? std::string("serial") : bus.name;
}

const StationSummary* find_station(const BusReport& r, std::uint8_t station) {
  for (const StationSummary& s : r.stations) {
    if (s.station == station) return &s;
  }
  return nullptr;
}

std::uint64_t frames_of(const StationSummary& s) {
  return s.requests + s.responses + s.bad_checks;
}

std::string fixed(double value, int decimals) {
  std::string o;
  append_fixed(o, value, decimals);
  return o;
}

// "fc 0x03 start 1050 count 7": a poll block as the text report writes it, on one line.
std::string block_detail(const AuditSettings& settings, const PollBlock& b) {
  std::string o = "fc ";
  append_hex_byte(o, b.function);
  o += ' ';
  std::string text = block_text(settings, b);
  // block_text pads its columns for a table; one space apart here.
  std::string squeezed;
  for (char c : text) {
    if (c == ' ' && (squeezed.empty() || squeezed.back() == ' ')) continue;
    squeezed += c;
  }
  while (!squeezed.empty() && squeezed.back() == ' ') squeezed.pop_back();
  return o + squeezed;
}

// Percent of `base` that `delta` is; infinite where base is 0 and delta is not.
double percent_of(double delta, double base) {
  if (base == 0) return delta == 0 ? 0 : INFINITY;
  return std::fabs(delta) / std::fabs(base) * 100;
}

// Where one bus of each side is compared, and where differences go.
class BusComparison {
 public:
  BusComparison(const DiffThresholds& t, const AuditReport& before_report,
                const AuditReport& after_report, std::vector<Difference>& out)
      : t_(t), before_report_(before_report), after_report_(after_report), out_(out) {}

  void compare(const BusFindings& before, const BusFindings& after, const RegisterRangeMap& b,
               const RegisterRangeMap& a) {
    label_ = bus_label(after);
    before_minutes_ = minutes(before_report_, before.report);
    after_minutes_ = minutes(after_report_, after.report);
    bus_rates(before.report, after.report);
    std::set<std::uint8_t> stations;
    for (const StationSummary& s : before.report.stations) stations.insert(s.station);
    for (const StationSummary& s : after.report.stations) stations.insert(s.station);
    for (std::uint8_t station : stations) {
      const StationSummary* sb = find_station(before.report, station);
      const StationSummary* sa = find_station(after.report, station);
      if (sb == nullptr || sa == nullptr) {
        presence(station, sb, sa);
        continue;
      }
      station_rates(*sb, *sa);
      latency(*sb, *sa);
      polls(station, before.report, after.report);
      values(station, before.name, after.name, b, a);
    }
  }

 private:
  // The minutes a bus's bytes span, or 0 where the side has no time.
  static double minutes(const AuditReport& report, const BusReport& bus) {
    if (!report.settings.has_timestamps || !bus.has_timestamps) return 0;
    return std::max(0.0, bus.last_time - bus.first_time) / 60;
  }

  Difference& add(std::optional<std::uint8_t> station, std::string what) {
    Difference d;
    d.bus = label_;
    d.station = station;
    d.what = std::move(what);
    out_.push_back(std::move(d));
    return out_.back();
  }

  // k events in n (frames, requests, minutes) on each side, as a rate per `scale` of n.
  void rate(std::optional<std::uint8_t> station, std::string what, std::string unit, double kb,
            double nb, double ka, double na, double scale, double absolute, double relative) {
    if (nb <= 0 || na <= 0) return;
    const double rb = kb / nb * scale;
    const double ra = ka / na * scale;
    const double delta = ra - rb;
    if (std::fabs(delta) <= absolute) return;
    if (percent_of(delta, rb) <= relative) return;
    if (!beyond_poisson_noise(kb, nb, ka, na, t_.noise_sigmas)) return;
    Difference& d = add(station, std::move(what));
    d.before = rb;
    d.after = ra;
    d.unit = std::move(unit);
    d.reason = fixed(kb, 0) + " in " + fixed(nb, 0) + " before, " + fixed(ka, 0) + " in " +
               fixed(na, 0) + " after, beyond " + fixed(t_.noise_sigmas, 1) +
               " sd of sampling noise";
  }

  void bus_rates(const BusReport& b, const BusReport& a) {
    rate(std::nullopt, "noise_bytes_per_1000_bytes", "per 1000 bytes",
         static_cast<double>(b.bytes.noise_bytes), static_cast<double>(b.bytes.bytes_in),
         static_cast<double>(a.bytes.noise_bytes), static_cast<double>(a.bytes.bytes_in), 1000,
         t_.rate_per_1000, t_.rate_percent);
    rate(std::nullopt, "unattributed_bad_checks_per_1000_frames", "per 1000 frames",
         static_cast<double>(b.unknown_station.damaged_frames), static_cast<double>(b.bytes.frames),
         static_cast<double>(a.unknown_station.damaged_frames), static_cast<double>(a.bytes.frames),
         1000, t_.rate_per_1000, t_.rate_percent);
  }

  void station_rates(const StationSummary& b, const StationSummary& a) {
    const auto d = [](std::uint64_t n) { return static_cast<double>(n); };
    rate(b.station, "requests_per_minute", "per minute", d(b.requests), before_minutes_,
         d(a.requests), after_minutes_, 1, 0, t_.requests_percent);
    rate(b.station, "bad_checks_per_1000_frames", "per 1000 frames", d(b.bad_checks),
         d(frames_of(b)), d(a.bad_checks), d(frames_of(a)), 1000, t_.rate_per_1000,
         t_.rate_percent);
    rate(b.station, "timeouts_per_1000_requests", "per 1000 requests", d(b.timeouts), d(b.requests),
         d(a.timeouts), d(a.requests), 1000, t_.rate_per_1000, t_.rate_percent);
    rate(b.station, "exceptions_per_1000_requests", "per 1000 requests", d(b.exceptions),
         d(b.requests), d(a.exceptions), d(a.requests), 1000, t_.rate_per_1000, t_.rate_percent);
  }

  void presence(std::uint8_t station, const StationSummary* b, const StationSummary* a) {
    Difference& d = add(station, "station");
    d.unit = "frames";
    if (b != nullptr) {
      d.before = static_cast<double>(frames_of(*b));
      d.reason = "vanished, " + fixed(*d.before, 0) + " frames before, none after";
    } else {
      d.after = static_cast<double>(frames_of(*a));
      d.reason = "appeared, none before, " + fixed(*d.after, 0) + " frames after";
    }
  }

  // A figure in ms that differs beyond `ms` and `percent` of its before value.
  void figure(std::uint8_t station, std::string what, std::string detail, double before_ms,
              double after_ms, double ms, double percent) {
    const double delta = after_ms - before_ms;
    if (std::fabs(delta) <= ms || percent_of(delta, before_ms) <= percent) return;
    Difference& d = add(station, std::move(what));
    d.detail = std::move(detail);
    d.before = before_ms;
    d.after = after_ms;
    d.unit = "ms";
    d.reason = "more than " + fixed(ms, 1) + " ms and " + fixed(percent, 0) + " %";
  }

  void latency(const StationSummary& b, const StationSummary& a) {
    if (b.latency.count < DiffThresholds::kMinLatencies ||
        a.latency.count < DiffThresholds::kMinLatencies) {
      return;
    }
    figure(b.station, "latency_p50", "", b.latency.p50 * 1e3, a.latency.p50 * 1e3, t_.latency_ms,
           t_.latency_percent);
    figure(b.station, "latency_p95", "", b.latency.p95 * 1e3, a.latency.p95 * 1e3, t_.latency_ms,
           t_.latency_percent);
  }

  // The station's poll blocks: blocks the master began or stopped polling, and the period
  // and jitter of those it polls on both sides.
  void polls(std::uint8_t station, const BusReport& b, const BusReport& a) {
    std::map<PollBlock, std::pair<const PollPeriod*, const PollPeriod*>> blocks;
    for (const PollPeriod& p : b.timing.poll_periods) {
      if (p.block.station == station) blocks[p.block].first = &p;
    }
    for (const PollPeriod& p : a.timing.poll_periods) {
      if (p.block.station == station) blocks[p.block].second = &p;
    }
    for (const auto& [block, sides] : blocks) {
      const auto [pb, pa] = sides;
      std::string detail = block_detail(after_report_.settings, block);
      if (pb == nullptr || pa == nullptr) {
        const PollPeriod& only = pb != nullptr ? *pb : *pa;
        // A block requested once may be a retry or a one-off read, not a poll.
        if (only.period.intervals == 0) continue;
        Difference& d = add(station, "poll_block");
        d.detail = std::move(detail);
        d.unit = "requests";
        const double requests = static_cast<double>(only.period.intervals + 1);
        (pb != nullptr ? d.before : d.after) = requests;
        d.reason = pb != nullptr ? "no longer polled (" + fixed(requests, 0) + " requests before)"
                                 : "newly polled (" + fixed(requests, 0) + " requests after)";
        continue;
      }
      if (pb->period.intervals < 2 || pa->period.intervals < 2) continue;
      figure(station, "poll_period", detail, pb->period.mean * 1e3, pa->period.mean * 1e3,
             t_.period_ms, t_.period_percent);
      figure(station, "poll_jitter", detail, pb->period.stddev * 1e3, pa->period.stddev * 1e3,
             t_.jitter_ms, t_.jitter_percent);
    }
  }

  // Registers of the station read on both sides whose after-range leaves the before-range.
  void values(std::uint8_t station, const std::string& before_bus, const std::string& after_bus,
              const RegisterRangeMap& b, const RegisterRangeMap& a) {
    for (auto it = a.lower_bound(RegisterKey{after_bus, station, Dialect{}, 0});
         it != a.end() && it->first.bus == after_bus && it->first.station == station; ++it) {
      RegisterKey key = it->first;
      key.bus = before_bus;
      const auto found = b.find(key);
      if (found == b.end()) continue;
      const ValueRange& rb = found->second;
      const ValueRange& ra = it->second;
      const double size = std::max({rb.max - rb.min, std::fabs(rb.min), std::fabs(rb.max)});
      const double slack = size * t_.value_percent / 100;
      if (ra.min >= rb.min - slack && ra.max <= rb.max + slack) continue;
      Difference& d = add(station, "register_range");
      std::string address = "0x";
      static constexpr char kHex[] = "0123456789ABCDEF";
      for (int shift = 12; shift >= 0; shift -= 4) address += kHex[(key.address >> shift) & 0xF];
      d.detail = std::string(to_string(key.dialect)) + " " + address;
      if (!ra.name.empty()) d.detail += " " + ra.name;
      d.before = rb.max;
      d.after = ra.max;
      d.unit = ra.unit;
      d.reason = "range " + fixed(rb.min, 3) + " .. " + fixed(rb.max, 3) + " before, " +
                 fixed(ra.min, 3) + " .. " + fixed(ra.max, 3) + " after, tolerance " +
                 fixed(slack, 3);
      d.counted = t_.count_values;
    }
  }

  const DiffThresholds& t_;
  const AuditReport& before_report_;
  const AuditReport& after_report_;
  std::vector<Difference>& out_;
  std::string label_;
  double before_minutes_ = 0;
  double after_minutes_ = 0;
};

const BusFindings* find_bus(const AuditReport& r, const std::string& name) {
  for (const BusFindings& bus : r.buses) {
    if (bus.name == name) return &bus;
  }
  return nullptr;
}

void bus_presence(const BusFindings& bus, bool before, std::vector<Difference>& out) {
  Difference d;
  d.bus = bus_label(bus);
  d.what = "bus";
  d.unit = "frames";
  const double frames = static_cast<double>(bus.report.bytes.frames);
  (before ? d.before : d.after) = frames;
  d.reason = before ? "vanished, " + fixed(frames, 0) + " frames before, none after"
                    : "appeared, none before, " + fixed(frames, 0) + " frames after";
  out.push_back(std::move(d));
}

}  // namespace

std::size_t DiffResult::counted() const {
  return static_cast<std::size_t>(std::count_if(differences.begin(), differences.end(),
                                                [](const Difference& d) { return d.counted; }));
}

bool beyond_poisson_noise(double k1, double n1, double k2, double n2, double sigmas) {
  if (n1 <= 0 || n2 <= 0) return false;
  const double shared = (k1 + k2) / (n1 + n2);
  const double sd = std::sqrt(shared * (1 / n1 + 1 / n2));
  const double delta = std::fabs(k2 / n2 - k1 / n1);
  if (sd == 0) return delta > 0;
  return delta > sigmas * sd;
}

DiffResult compare_sides(const DiffSide& before, const DiffSide& after,
                         const DiffThresholds& thresholds) {
  DiffResult result;
  BusComparison comparison(thresholds, before.report, after.report, result.differences);
  const auto& bb = before.report.buses;
  const auto& ab = after.report.buses;
  if (bb.size() == 1 && ab.size() == 1) {
    comparison.compare(bb.front(), ab.front(), before.ranges, after.ranges);
    return result;
  }
  for (const BusFindings& bus : bb) {
    if (find_bus(after.report, bus.name) == nullptr) bus_presence(bus, true, result.differences);
  }
  for (const BusFindings& bus : ab) {
    const BusFindings* earlier = find_bus(before.report, bus.name);
    if (earlier == nullptr) {
      bus_presence(bus, false, result.differences);
    } else {
      comparison.compare(*earlier, bus, before.ranges, after.ranges);
    }
  }
  return result;
}

}  // namespace pvtap::analyzer
