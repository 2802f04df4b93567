#include "outputs/ground_truth.h"

#include <fstream>
#include <sstream>

#include "outputs/json_text.h"

namespace pvtap::sim {
namespace {

void write_values(std::ostream& o, const std::vector<RegisterTruth>& values) {
  o << ",\"values\":[";
  for (std::size_t i = 0; i < values.size(); ++i) {
    const RegisterTruth& v = values[i];
    o << (i ? "," : "") << "{\"register\":\"" << v.address << "\",\"key\":\"" << v.key
      << "\",\"raw\":" << v.raw;
    if (!v.text.empty()) o << ",\"text\":\"" << v.text << "\"";
    if (v.numeric) o << ",\"value\":" << number(v.value);
    o << "}";
  }
  o << "]";
}

void write_event(std::ostream& o, const BusEvent& e) {
  if (e.kind == BusEvent::Kind::Noise) {
    o << "{\"type\":\"noise\",\"ts\":" << seconds(e.start) << ",\"bytes\":" << e.bytes.size()
      << ",\"hex\":\"" << hex(e.bytes) << "\"";
    // An ASCII frame damaged beyond delimiting: noise to a reader, named by its fault here.
    if (e.fault != "noise") o << ",\"fault\":\"" << e.fault << "\"";
    o << "}";
    return;
  }
  // ts is the first byte, as pvtap audit reports frames; end is the last byte.
  o << "{\"type\":\"frame\",\"ts\":" << seconds(e.start) << ",\"end\":" << seconds(e.end)
    << ",\"dialect\":\"" << to_string(e.dialect) << "\",\"role\":\"" << to_string(e.role)
    << "\",\"station\":" << int{e.station} << ",\"function\":" << int{e.function}
    << ",\"length\":" << e.bytes.size() << ",\"check\":\"" << (e.check_ok ? "ok" : "bad")
    << "\",\"hex\":\"" << hex(e.bytes) << "\"";
  if (!e.fault.empty()) o << ",\"fault\":\"" << e.fault << "\"";
  if (e.role == Role::Response)
    o << ",\"latency_ms\":" << number(static_cast<double>(e.latency) / 1e3);
  if (e.role == Role::Response && e.check_ok) write_values(o, e.values);
  if (e.master != 1) o << ",\"master\":" << int{e.master};
  o << "}";
}

// A shared bus: its masters, collisions, conflicts and echoes, written only when it has any
// (the older samples keep their bytes).
void write_shared_bus(std::ostream& o, const BusTimeline& t) {
  if (!t.masters.empty()) {
    o << ",\n\"masters\":[";
    for (std::size_t i = 0; i < t.masters.size(); ++i) {
      const MasterTruth& m = t.masters[i];
      o << (i ? ",\n" : "\n") << "{\"master\":" << int{m.master}
        << ",\"period_s\":" << number(m.period_s) << ",\"turnaround_ms\":["
        << number(static_cast<double>(m.turnaround_min) / 1e3) << ","
        << number(static_cast<double>(m.turnaround_max) / 1e3) << "],\"plan\":[";
      for (std::size_t k = 0; k < m.plan.size(); ++k) {
        const PollTruth& p = m.plan[k];
        o << (k ? "," : "") << "{\"station\":" << int{p.station}
          << ",\"function\":" << int{p.function} << ",\"start\":" << p.start
          << ",\"count\":" << p.count << "}";
      }
      o << "]}";
    }
    o << "]";
  }
  if (!t.masters.empty() || !t.collisions.empty()) {
    o << ",\n\"collisions\":[";
    for (std::size_t i = 0; i < t.collisions.size(); ++i) {
      const CollisionTruth& c = t.collisions[i];
      o << (i ? ",\n" : "\n") << "{\"ts\":" << seconds(c.start) << ",\"end\":" << seconds(c.end)
        << ",\"destroyed\":[";
      for (std::size_t k = 0; k < c.destroyed.size(); ++k) {
        const DestroyedExchange& x = c.destroyed[k];
        o << (k ? "," : "") << "{\"master\":" << int{x.master}
          << ",\"request_ts\":" << seconds(x.request_start) << ",\"station\":" << int{x.station}
          << ",\"function\":" << int{x.function} << ",\"lost\":\""
          << (x.request_lost ? "request" : "reply") << "\"}";
      }
      o << "]}";
    }
    o << "]";
  }
  if (!t.conflicts.empty()) {
    o << ",\n\"address_conflicts\":[";
    for (std::size_t i = 0; i < t.conflicts.size(); ++i)
      o << (i ? "," : "") << "{\"station\":" << int{t.conflicts[i].station}
        << ",\"second_replies\":" << t.conflicts[i].second_replies << "}";
    o << "]";
  }
  if (t.echoes > 0) o << ",\n\"echoes\":" << t.echoes;
}

struct Totals {
  std::size_t bytes = 0, frames = 0, requests = 0, responses = 0, bad = 0, noise = 0,
              exceptions = 0, damaged_replies = 0;
};

Totals count(const BusTimeline& t) {
  Totals n;
  for (const BusEvent& e : t.events) {
    n.bytes += e.bytes.size();
    if (e.kind == BusEvent::Kind::Noise) {
      n.noise += e.bytes.size();
      continue;
    }
    if (e.fault == "echo") continue;  // the tap's copy of a request: one request on the bus
    ++n.frames;
    ++(e.role == Role::Request ? n.requests : n.responses);
    if (!e.check_ok) ++n.bad;
    if (!e.check_ok && e.role == Role::Response) ++n.damaged_replies;
    if (e.role == Role::Response && e.fault == "error_reply") ++n.exceptions;
  }
  return n;
}

void write_config(std::ostream& o, const SimConfig& c) {
  o << "\"generator\":\"pvtap-sim\",\"seed\":" << c.seed << ",\"dialects\":[";
  for (std::size_t i = 0; i < c.dialects.size(); ++i)
    o << (i ? "," : "") << "\"" << to_string(c.dialects[i]) << "\"";
  o << "],\"inverters\":" << c.inverters << ",\"first_station\":" << int{c.first_station}
    << ",\"baud\":" << c.baud << ",\"timeout_s\":" << number(c.timeout_s) << ",\"faults\":{";
  for (unsigned k = 0; k < kFaultKinds; ++k) {
    const auto kind = static_cast<FaultKind>(k);
    if (!c.faults.drawn(kind)) continue;
    o << (k ? "," : "") << "\"" << to_string(kind) << "\":" << c.faults.percent[k];
  }
  o << "}";
}

// "layout":[{"function":4,"register":0,"words":2,"type":"float32","word_order":"high_first",
// "key":"voltage_l1"},...]: what the device's registers hold, when it says.
void write_layout(std::ostream& o, const std::vector<LayoutTruth>& layout) {
  if (layout.empty()) return;
  o << ",\"layout\":[";
  for (std::size_t i = 0; i < layout.size(); ++i) {
    const LayoutTruth& l = layout[i];
    o << (i ? "," : "") << "{\"function\":" << int{l.function} << ",\"register\":" << l.address
      << ",\"words\":" << int{l.words} << ",\"type\":\"" << l.type << "\"";
    if (l.words == 2)
      o << ",\"word_order\":\"" << (l.low_first ? "low_first" : "high_first") << "\"";
    if (l.counter) o << ",\"counter\":true";
    o << ",\"key\":\"" << l.key << "\"}";
  }
  o << "]";
}

// The plain Modbus devices, named only when there are any (the older samples keep their bytes).
void write_devices(std::ostream& o, const std::vector<DeviceTruth>& devices) {
  if (devices.empty()) return;
  o << ",\"devices\":[";
  for (std::size_t i = 0; i < devices.size(); ++i) {
    const DeviceTruth& d = devices[i];
    o << (i ? "," : "") << "{\"station\":" << int{d.station} << ",\"kind\":\"" << d.label.kind
      << "\"";
    if (!d.label.vendor.empty())
      o << ",\"vendor\":\"" << d.label.vendor << "\",\"product\":\"" << d.label.product
        << "\",\"revision\":\"" << d.label.revision << "\"";
    if (!d.label.name.empty()) o << ",\"name\":\"" << d.label.name << "\"";
    write_layout(o, d.layout);
    o << "}";
  }
  o << "]";
}

// A LAN carrier: "v5":{counts} and "v5_frames":[one object per carrier frame].
void write_lan(std::ostream& o, const LanTruth* lan) {
  if (!lan) return;
  o << ",\n\"" << lan->carrier << "\":{";
  for (std::size_t i = 0; i < lan->counts.size(); ++i)
    o << (i ? "," : "") << "\"" << lan->counts[i].first << "\":" << lan->counts[i].second;
  o << "},\n\"" << (lan->list_name.empty() ? lan->carrier + "_frames" : lan->list_name) << "\":[";
  for (std::size_t i = 0; i < lan->frames.size(); ++i) o << (i ? ",\n" : "\n") << lan->frames[i];
  o << "]";
}

void write_requests(std::ostream& o, const char* name, const std::vector<TimeoutTruth>& list) {
  o << "],\n\"" << name << "\":[";
  for (std::size_t i = 0; i < list.size(); ++i) {
    const TimeoutTruth& t = list[i];
    o << (i ? ",\n" : "\n") << "{\"request_ts\":" << seconds(t.request_start)
      << ",\"station\":" << int{t.station} << ",\"function\":" << int{t.function};
    if (!t.reason.empty()) o << ",\"reason\":\"" << t.reason << "\"";
    o << "}";
  }
}

}  // namespace

std::string write_ground_truth(const BusTimeline& timeline, const SimConfig& config,
                               const std::string& path, const LanTruth* lan) {
  std::ostringstream o;
  o << "{";
  write_config(o, config);
  write_devices(o, timeline.devices);
  write_lan(o, lan);
  write_shared_bus(o, timeline);
  o << ",\n\"events\":[\n";
  for (std::size_t i = 0; i < timeline.events.size(); ++i) {
    write_event(o, timeline.events[i]);
    o << (i + 1 < timeline.events.size() ? ",\n" : "\n");
  }
  write_requests(o, "timeouts", timeline.timeouts);
  write_requests(o, "unanswered_damaged_requests", timeline.unanswered_damaged_requests);
  o << "],\n\"faults\":[";
  for (std::size_t i = 0; i < timeline.faults.size(); ++i) {
    const FaultTruth& f = timeline.faults[i];
    o << (i ? ",\n" : "\n") << "{\"ts\":" << seconds(f.time) << ",\"station\":" << int{f.station}
      << ",\"kind\":\"" << f.kind << "\"}";
  }
  write_requests(o, "unanswered_at_end", timeline.unanswered_at_end);
  const Totals n = count(timeline);
  o << "],\n\"summary\":{\"bytes\":" << n.bytes << ",\"frames\":" << n.frames
    << ",\"requests\":" << n.requests << ",\"responses\":" << n.responses
    << ",\"bad_checks\":" << n.bad << ",\"timeouts\":" << timeline.timeouts.size()
    << ",\"damaged_replies\":" << n.damaged_replies
    << ",\"unanswered_damaged_requests\":" << timeline.unanswered_damaged_requests.size()
    << ",\"noise_bytes\":" << n.noise << ",\"exceptions\":" << n.exceptions << "}}\n";
  std::ofstream file(path, std::ios::binary);
  file << o.str();
  return file ? std::string{} : "cannot write " + path;
}

}  // namespace pvtap::sim
