// One JSON object per line: frames, timeouts, noise and gaps (the summary line is written by
// json_summary.cpp).
#include <array>
#include <string>
#include <vector>

#include "formatting/json_writer.h"
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
    for (const Dialect d : kAllDialects) {
      for (const Role r : {Role::Request, Role::Response}) {
        JsonWriter head = JsonWriter::more_members(frame_heads_[head_index(d, r)]);
        head.field_plain("dialect", to_string(d));
        head.field_plain("role", to_string(r));
        head.key("station");
      }
    }
  }

  void frame(const EventContext& c, const SessionFrame& f) override {
    JsonWriter w = begin_line("frame", c, f.start_time);
    w.raw_members(frame_heads_[head_index(f.dialect, f.role)]);
    write_station_and_function(w, f);
    w.field("length", f.bytes.size());
    if (f.check.carried) {
      w.field_plain("check", "tcp");  // no check on the wire: TCP's vouched
    } else if (f.check.ok) {
      w.field_plain("check", "ok");
    } else {
      w.field_plain("check", "bad");
      w.field_hex("check_expected", check_wire_bytes(f.dialect, f.check.expected));
    }
    w.field_hex("raw", f.bytes);
    if (f.latency) w.field_fixed("latency_ms", *f.latency * 1e3, 3);
    w.begin_array("values");
    const std::uint8_t station = f.frame != nullptr ? f.frame->station : 0;
    for (const DecodedValue& v : f.values) values_.write(w, v, f.dialect, station);
    w.end_array();
    {
      // A writer of its own for the contents: `w` is not handed on, so stays in registers.
      JsonWriter contents = JsonWriter::more_members(w.buffer());
      write_contents_json(contents, f);
    }
    if (f.echo) w.field_bool("echo", true);
    w.begin_array("issues");
    collect_issues(f, issues_);
    for (const std::string& issue : issues_) w.string(issue);
    w.end_array();
    end_line(w, c);
  }

  void timeout(const EventContext& c, const SessionTimeout& t) override {
    JsonWriter w =
        begin_line(t.kind == UnansweredKind::Timeout ? "timeout" : "unanswered", c, t.time);
    w.key("request_ts");
    write_time(w, c, t.request_start);
    w.field_plain("dialect", to_string(t.timeout.dialect));
    w.field("station", t.timeout.station);
    w.field("function", t.timeout.function);
    w.field_plain("reason", unanswered_reason(t));
    if (t.kind == UnansweredKind::Timeout && t.timeout.reason == TimeoutReason::CarrierNoReply) {
      w.field("carrier_reason", solarman_v5::no_reply_reason(t.timeout.carrier_code));
    }
    if (c.has_timestamps) w.field_fixed("waited_ms", t.timeout.waited * 1e3, 3);
    end_line(w, c);
  }

  void noise(const EventContext& c, const SessionNoise& n) override {
    JsonWriter w = begin_line("noise", c, n.noise.start_time);
    w.field("bytes", n.noise.bytes.size());
    w.field("offset", n.noise.offset);
    w.field_hex("raw", n.noise.bytes);
    end_line(w, c);
  }

  void driver_glitch(const EventContext& c, const SessionDriverGlitch& g) override {
    JsonWriter w = begin_line("driver_glitch", c, g.time);
    w.field_hex("raw", std::span(&g.value, 1));
    w.field_plain("switching", g.switch_on ? "on" : "off");
    w.field_bool("framing_error", g.framing_error);
    end_line(w, c);
  }

  void line_error(const EventContext& c, const SessionLineError& e) override {
    JsonWriter w = begin_line("line_error", c, e.time);
    w.field_plain("error", line_error_name(e.kind));
    if (e.kind != LineErrorKind::Break) w.field_hex("raw", std::span(&e.value, 1));
    w.field_fixed("duration_us", e.duration * 1e6, 1);
    end_line(w, c);
  }

  void gap(const EventContext& c, const SessionGap& g) override {
    JsonWriter w = begin_line("gap", c, g.time);
    w.key("bytes");
    if (g.lost_bytes) {
      w.uint(*g.lost_bytes);
    } else {
      w.null();
    }
    w.field_plain("direction", direction_key(g.direction));
    end_line(w, c);
  }

  // {"type":"collision","ts":...,"end":...,"late":false}: `late` when it was named after the
  // fact, once the second master showed.
  void collision(const EventContext& c, const SessionCollision& k) override {
    JsonWriter w = begin_line("collision", c, k.start_time);
    w.key("end");
    write_time(w, c, k.end_time);
    w.field_bool("late", k.late);
    end_line(w, c);
  }

 private:
  [[gnu::always_inline]] static void write_time(JsonWriter& w, const EventContext& c, double time) {
    if (c.has_timestamps) {
      w.fixed(time, 6);
    } else {
      w.null();
    }
  }
  // Inlined always, as is end_line: the line's writer is a local of each event's function.
  [[gnu::always_inline]] JsonWriter begin_line(std::string_view type, const EventContext& c,
                                               double time) {
    // Lines of one type come in runs: {"type":"frame","ts": is kept, not written each time.
    if (type.data() != line_type_.data() || type.size() != line_type_.size()) {
      set_line_type(type);
    }
    JsonWriter w(out_.buffer());
    w.raw_object_start(line_head_);
    write_time(w, c, time);
    return w;
  }
  [[gnu::noinline]] void set_line_type(std::string_view type) {
    line_type_ = type;
    line_head_.clear();
    JsonWriter head(line_head_);
    head.begin_object();
    head.field_plain("type", type);
    head.key("ts");
  }
  [[gnu::always_inline]] void end_line(JsonWriter& w, const EventContext& c) {
    if (!c.bus.empty()) {
      // Lines of one bus come in runs: its quoted name is kept, not escaped for every line.
      if (c.bus != bus_name_) set_bus(c.bus);
      // The line has members (type, ts): the kept `,"bus":"a"}` ends it, newline and all.
      w.buffer() += bus_tail_;
    } else {
      w.end_object();
      w.buffer() += '\n';
    }
    out_.done();
  }
  [[gnu::noinline]] void set_bus(std::string_view bus) {
    bus_name_.assign(bus);
    bus_tail_.assign(1, ',');
    JsonWriter(bus_tail_).field("bus", bus);
    bus_tail_ += "}\n";
  }
  static std::size_t head_index(Dialect d, Role r) {
    return static_cast<std::size_t>(d) * 2 + static_cast<std::size_t>(r);
  }
  [[gnu::always_inline]] static void write_station_and_function(JsonWriter& w,
                                                                const SessionFrame& f) {
    if (f.frame == nullptr) {
      w.null();
      w.field_null("function");
      return;
    }
    w.uint(f.frame->station);
    w.field("function", f.frame->function);
  }

  OutputStream& out_;
  // ,"dialect":"gsl","role":"response","station": for each dialect and role, written once.
  std::array<std::string, kDialectCount * 2> frame_heads_;
  ValueJsonCache values_;
  std::vector<std::string> issues_;
  std::string bus_name_;
  std::string bus_tail_;        // ,"bus":"a"}\n
  std::string_view line_type_;  // a literal of this file, so its address names it
  std::string line_head_;
};

}  // namespace

std::unique_ptr<EventWriter> make_jsonl_event_writer(OutputStream& out) {
  return std::make_unique<JsonlEventWriter>(out);
}

}  // namespace pvtap::analyzer
