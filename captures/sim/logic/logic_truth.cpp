#include "logic/logic_truth.h"

#include <cmath>
#include <map>
#include <sstream>

#include "outputs/json_text.h"

namespace pvtap::sim {
namespace {

std::string talker_name(int talker) {
  return talker == 0 ? "\"master\"" : std::to_string(talker);
}

Micros at(const LogicLayout& l, double t) {
  return l.origin + std::llround(t);
}

std::string session_object(const LogicLayout& l, const LogicSignals& s, const LogicOptions& o,
                           unsigned baud) {
  std::ostringstream j;
  j << "{\"kind\":\"session\",\"ts\":" << seconds(l.origin)
    << ",\"sample_rate\":" << number(s.sample_rate) << ",\"samples\":" << s.samples
    << ",\"baud\":" << baud << ",\"format\":\"" << format_name(o.format)
    << "\",\"inverted\":" << (o.format.inverted ? "true" : "false")
    << ",\"clock_deviation_pct\":" << number(o.clock_deviation_pct)
    << ",\"jitter_pct\":" << number(o.jitter_pct);
  if (o.undriven_space) j << ",\"undriven\":\"space\"";
  j << ",\"channels\":[";
  for (std::size_t i = 0; i < s.channels.size(); ++i)
    j << (i ? "," : "") << "\"" << s.channels[i].name << "\"";
  j << "]}";
  return j.str();
}

// Each talker's turnaround: how long after its last stop bit it releases the driver.
void driver_objects(const LogicLayout& l, std::vector<std::string>& out) {
  std::map<int, std::pair<double, std::uint64_t>> by_talker;
  for (const DriverWindow& w : l.drivers) {
    by_talker[w.talker].first = w.release;
    ++by_talker[w.talker].second;
  }
  for (const auto& [talker, d] : by_talker)
    out.push_back("{\"kind\":\"driver\",\"talker\":" + talker_name(talker) +
                  ",\"release_us\":" + number(d.first) + ",\"frames\":" + std::to_string(d.second) +
                  ",\"truncated\":" + (d.first < 0 ? "true" : "false") + "}");
}

}  // namespace

LanTruth logic_truth(const LogicLayout& l, const LogicSignals& s, const LogicOptions& o,
                     unsigned baud) {
  LanTruth t;
  t.carrier = "logic";
  t.list_name = "logic_events";
  std::uint64_t on = 0, early = 0;
  for (const GlitchPulse& g : l.glitches) on += g.switch_on ? 1u : 0u;
  for (const Violation& v : l.violations) early += v.kind == "early_reply" ? 1u : 0u;
  t.counts = {{"driver_glitches", l.glitches.size()},
              {"switch_on_glitches", on},
              {"switch_off_glitches", l.glitches.size() - on},
              {"early_replies", early},
              {"pauses_in_frames", l.violations.size() - early}};
  t.frames.push_back(session_object(l, s, o, baud));
  driver_objects(l, t.frames);
  for (const GlitchPulse& g : l.glitches) {
    const std::uint8_t v = g.value;
    t.frames.push_back("{\"kind\":\"driver_glitch\",\"ts\":" + seconds(at(l, g.start)) +
                       ",\"value\":\"" + hex(std::span(&v, 1)) + "\",\"switching\":\"" +
                       (g.switch_on ? "on" : "off") + "\",\"talker\":" + talker_name(g.talker) +
                       "}");
  }
  for (const Violation& v : l.violations)
    t.frames.push_back("{\"kind\":\"" + v.kind + "\",\"ts\":" + seconds(at(l, v.start)) +
                       ",\"station\":" + std::to_string(v.station) + "}");
  return t;
}

}  // namespace pvtap::sim
