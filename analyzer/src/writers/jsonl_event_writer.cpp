// One JSON object per line: frames, timeouts, noise and gaps (the summary line is written by
// json_summary.cpp).
#include <array>
#include <string>
#include <vector>

#include "formatting/json_text.h"
#include "formatting/number_text.h"
#include "pvtap/carriers/solarman_v5_pairing.h"
#include "report/frame_contents.h"
#include "report/frame_findings.h"
#include "writers/event_writers.h"
#include "writers/value_json_cache.h"

namespace pvtap::analyzer {
namespace {

std::string_view direction_key(Direction d) {
  switch (d) {
    case Direction::ToSlave:
      return "to_slave";
    case Direction::FromSlave:
      return "from_slave";
    default:
      return "unknown";
  }
}

class JsonlEventWriter : public EventWriter {
 public:
  explicit JsonlEventWriter(OutputStream& out) : out_(out) {
    for (const Dialect d : {Dialect::Ascii, Dialect::Hybrid, Dialect::Gsl, Dialect::Modbus}) {
      for (const Role r : {Role::Request, Role::Response}) {
        std::string& head = frame_heads_[head_index(d, r)];
        head = ",\"dialect\":\"";
        head += to_string(d);
        head += "\",\"role\":\"";
        head += to_string(r);
        head += "\",\"station\":";
      }
    }
  }

  void frame(const EventContext& c, const SessionFrame& f) override {
    std::string& o = out_.buffer();
    begin_line(o, "frame", c, f.start_time);
    o += frame_heads_[head_index(f.dialect, f.role)];
    append_station_and_function(o, f);
    o += ",\"length\":";
    append_uint(o, f.bytes.size());
    if (f.check.carried) {
      o += ",\"check\":\"tcp\",\"raw\":\"";  // no check on the wire: TCP's vouched
    } else if (f.check.ok) {
      o += ",\"check\":\"ok\",\"raw\":\"";
    } else {
      o += ",\"check\":\"bad\",\"check_expected\":\"";
      append_hex(o, check_wire_bytes(f.dialect, f.check.expected));
      o += "\",\"raw\":\"";
    }
    append_hex(o, f.bytes);
    o += '"';
    if (f.latency) {
      o += ",\"latency_ms\":";
      append_fixed(o, *f.latency * 1e3, 3);
    }
    o += ",\"values\":[";
    for (std::size_t i = 0; i < f.values.size(); ++i) {
      if (i > 0) o += ',';
      values_.append(o, f.values[i], f.dialect);
    }
    o += ']';
    append_contents_json(o, f);
    if (f.echo) o += ",\"echo\":true";
    o += ",\"issues\":[";
    collect_issues(f, issues_);
    for (std::size_t i = 0; i < issues_.size(); ++i) {
      if (i > 0) o += ',';
      append_json_string(o, issues_[i]);
    }
    o += ']';
    end_line(o, c);
  }

  void timeout(const EventContext& c, const SessionTimeout& t) override {
    std::string& o = out_.buffer();
    begin_line(o, t.kind == UnansweredKind::Timeout ? "timeout" : "unanswered", c, t.time);
    o += ",\"request_ts\":";
    append_time(o, c, t.request_start);
    o += ",\"dialect\":\"";
    o += to_string(t.timeout.dialect);
    o += "\",\"station\":";
    append_uint(o, t.timeout.station);
    o += ",\"function\":";
    append_uint(o, t.timeout.function);
    o += ",\"reason\":\"";
    o += unanswered_reason(t);
    o += '"';
    if (t.kind == UnansweredKind::Timeout && t.timeout.reason == TimeoutReason::CarrierNoReply) {
      o += ",\"carrier_reason\":";
      append_json_string(o, solarman_v5::no_reply_reason(t.timeout.carrier_code));
    }
    if (c.has_timestamps) {
      o += ",\"waited_ms\":";
      append_fixed(o, t.timeout.waited * 1e3, 3);
    }
    end_line(o, c);
  }

  void noise(const EventContext& c, const SessionNoise& n) override {
    std::string& o = out_.buffer();
    begin_line(o, "noise", c, n.noise.start_time);
    o += ",\"bytes\":";
    append_uint(o, n.noise.bytes.size());
    o += ",\"offset\":";
    append_uint(o, n.noise.offset);
    o += ",\"raw\":\"";
    append_hex(o, n.noise.bytes);
    o += '"';
    end_line(o, c);
  }

  void driver_glitch(const EventContext& c, const DriverGlitchEvent& g) override {
    std::string& o = out_.buffer();
    begin_line(o, "driver_glitch", c, g.time);
    o += ",\"raw\":\"";
    append_hex(o, std::span(&g.value, 1));
    o += g.switch_on ? "\",\"switching\":\"on\"" : "\",\"switching\":\"off\"";
    o += g.framing_error ? ",\"framing_error\":true" : ",\"framing_error\":false";
    end_line(o, c);
  }

  void line_error(const EventContext& c, const LineErrorEvent& e) override {
    std::string& o = out_.buffer();
    begin_line(o, "line_error", c, e.time);
    o += ",\"error\":\"";
    o += line_error_name(e.kind);
    o += '"';
    if (e.kind != LineErrorEvent::Kind::line_break) {
      o += ",\"raw\":\"";
      append_hex(o, std::span(&e.value, 1));
      o += '"';
    }
    o += ",\"duration_us\":";
    append_fixed(o, e.duration * 1e6, 1);
    end_line(o, c);
  }

  void gap(const EventContext& c, const SessionGap& g) override {
    std::string& o = out_.buffer();
    begin_line(o, "gap", c, g.time);
    o += ",\"bytes\":";
    if (g.lost_bytes) {
      append_uint(o, *g.lost_bytes);
    } else {
      o += "null";
    }
    o += ",\"direction\":\"";
    o += direction_key(g.direction);
    o += '"';
    end_line(o, c);
  }

  // {"type":"collision","ts":...,"end":...,"late":false}: `late` when it was named after the
  // fact, once the second master showed.
  void collision(const EventContext& c, const SessionCollision& k) override {
    std::string& o = out_.buffer();
    begin_line(o, "collision", c, k.start_time);
    o += ",\"end\":";
    append_time(o, c, k.end_time);
    o += k.late ? ",\"late\":true" : ",\"late\":false";
    end_line(o, c);
  }

 private:
  static void append_time(std::string& o, const EventContext& c, double time) {
    if (c.has_timestamps) {
      append_fixed(o, time, 6);
    } else {
      o += "null";
    }
  }
  static void begin_line(std::string& o, std::string_view type, const EventContext& c,
                         double time) {
    o += "{\"type\":\"";
    o += type;
    o += "\",\"ts\":";
    append_time(o, c, time);
  }
  void end_line(std::string& o, const EventContext& c) {
    if (!c.bus.empty()) {
      // Lines of one bus come in runs: its quoted name is kept, not escaped for every line.
      if (c.bus != bus_name_) {
        bus_name_.assign(c.bus);
        bus_field_ = ",\"bus\":";
        append_json_string(bus_field_, c.bus);
      }
      o += bus_field_;
    }
    o += "}\n";
    out_.done();
  }
  static std::size_t head_index(Dialect d, Role r) {
    return static_cast<std::size_t>(d) * 2 + static_cast<std::size_t>(r);
  }
  static void append_station_and_function(std::string& o, const SessionFrame& f) {
    if (f.frame == nullptr) {
      o += "null,\"function\":null";
      return;
    }
    append_uint(o, f.frame->station);
    o += ",\"function\":";
    append_uint(o, f.frame->function);
  }

  OutputStream& out_;
  // ,"dialect":"gsl","role":"response","station": for each dialect and role, written once.
  std::array<std::string, kDialectCount * 2> frame_heads_;
  ValueJsonCache values_;
  std::vector<std::string> issues_;
  std::string bus_name_;
  std::string bus_field_;
};

}  // namespace

std::unique_ptr<EventWriter> make_jsonl_event_writer(OutputStream& out) {
  return std::make_unique<JsonlEventWriter>(out);
}

}  // namespace pvtap::analyzer
