// One readable line per frame, timeout, noise run and gap.
#include <cctype>
#include <string>
#include <vector>

#include "formatting/number_text.h"
#include "pvtap/carriers/solarman_v5_pairing.h"
#include "report/frame_contents.h"
#include "report/frame_findings.h"
#include "writers/event_writers.h"

namespace pvtap::analyzer {
namespace {

void pad_to(std::string& o, std::size_t line_start, std::size_t column) {
  const std::size_t used = o.size() - line_start;
  o.append(used < column ? column - used : 1, ' ');
}

class TextEventWriter : public EventWriter {
 public:
  explicit TextEventWriter(OutputStream& out) : out_(out) {}

  void frame(const EventContext& c, const SessionFrame& f) override {
    std::string& o = out_.buffer();
    const std::size_t start = begin_line(o, c, f.start_time, f.offset);
    o += to_string(f.dialect);
    pad_to(o, start, 8);
    if (f.frame == nullptr) {
      o += "malformed";
    } else {
      o += "st ";
      append_uint(o, f.frame->station);
      pad_to(o, start, 16);
      o += f.echo ? "echo" : to_string(f.role);
      pad_to(o, start, 26);
      append_function(o, f.dialect, f.frame->function);
    }
    o += "  ";
    append_uint(o, f.bytes.size());
    o += " B";
    append_check(o, f);
    if (f.latency) {
      o += "  ";
      append_fixed(o, *f.latency * 1e3, 1);
      o += " ms";
    }
    append_values(o, f);
    append_contents_text(o, f);
    collect_issues(f, issues_);
    for (const std::string& issue : issues_) {
      o += "  [";
      o += issue;
      o += ']';
    }
    o += '\n';
    out_.done();
  }

  void timeout(const EventContext& c, const SessionTimeout& t) override {
    std::string& o = out_.buffer();
    const std::size_t start = begin_line(o, c, t.time, 0);
    o += to_string(t.timeout.dialect);
    pad_to(o, start, 8);
    o += "st ";
    append_uint(o, t.timeout.station);
    pad_to(o, start, 16);
    o += t.kind == UnansweredKind::Timeout ? "TIMEOUT" : "unanswered";
    pad_to(o, start, 26);
    append_function(o, t.timeout.dialect, t.timeout.function);
    o += "  ";
    append_wait(o, c, t);
    o += '\n';
    out_.done();
  }

  void noise(const EventContext& c, const SessionNoise& n) override {
    std::string& o = out_.buffer();
    const std::size_t start = begin_line(o, c, n.noise.start_time, n.noise.offset);
    o += "noise";
    pad_to(o, start, 8);
    append_uint(o, n.noise.bytes.size());
    o += " B  ";
    constexpr std::size_t kShown = 32;
    append_spaced_hex(o, n.noise.bytes.first(std::min(n.noise.bytes.size(), kShown)));
    if (n.noise.bytes.size() > kShown) o += " ...";
    o += '\n';
    out_.done();
  }

  void driver_glitch(const EventContext& c, const SessionDriverGlitch& g) override {
    std::string& o = out_.buffer();
    const std::size_t start = begin_line(o, c, g.time, 0);
    o += "glitch";
    pad_to(o, start, 8);
    append_spaced_hex(o, std::span(&g.value, 1));
    o += g.switch_on ? "  driver switching on" : "  driver switching off";
    if (g.framing_error) o += ", framing error";
    o += '\n';
    out_.done();
  }

  void line_error(const EventContext& c, const SessionLineError& e) override {
    std::string& o = out_.buffer();
    const std::size_t start = begin_line(o, c, e.time, 0);
    o += "line";
    pad_to(o, start, 8);
    if (e.kind != LineErrorKind::Break) {
      append_spaced_hex(o, std::span(&e.value, 1));
      o += "  ";
    }
    o += line_error_name(e.kind);
    o += '\n';
    out_.done();
  }

  void gap(const EventContext& c, const SessionGap& g) override {
    std::string& o = out_.buffer();
    const std::size_t start = begin_line(o, c, g.time, 0);
    o += "GAP";
    pad_to(o, start, 8);
    if (g.lost_bytes) {
      append_uint(o, *g.lost_bytes);
      o += " bytes of capture data lost";
    } else {
      o += "capture data lost (size unknown)";
    }
    if (g.direction == Direction::ToSlave) o += " (master to slave)";
    if (g.direction == Direction::FromSlave) o += " (slave to master)";
    o += '\n';
    out_.done();
  }

  void collision(const EventContext& c, const SessionCollision& k) override {
    std::string& o = out_.buffer();
    const std::size_t start = begin_line(o, c, k.start_time, 0);
    o += "COLL";
    pad_to(o, start, 8);
    o += "collision: two transmissions at once garbled the bus (more than one master)";
    if (k.late) o += "; named once the second master showed";
    o += '\n';
    out_.done();
  }

 private:
  // Time of day (seconds from a logic recording's start, which has no wall clock; the stream
  // offset for inputs without time), then the bus; returns where the event's own columns
  // start, so that they line up whatever the prefix.
  static std::size_t begin_line(std::string& o, const EventContext& c, double time,
                                std::uint64_t offset) {
    const std::size_t start = o.size();
    if (c.from_recording_start) {
      o += '+';
      append_fixed(o, time, 6);
      o += " s";
      pad_to(o, start, 15);  // as wide as a time of day
    } else if (c.has_timestamps) {
      append_time_of_day(o, time);
    } else {
      o += '@';
      append_uint(o, offset);
      pad_to(o, start, 15);  // as wide as a time of day
    }
    o += "  ";
    if (!c.bus.empty()) {
      o += c.bus;
      o += "  ";
    }
    return o.size();
  }
  static void append_check(std::string& o, const SessionFrame& f) {
    if (f.check.carried) {
      o += "  tcp";  // no check on the wire: TCP's vouched for the bytes
      return;
    }
    if (f.check.ok) {
      o += "  ok";
      return;
    }
    o += "  BAD ";
    for (const char c : check_name(f.dialect)) o += static_cast<char>(std::toupper(c));
    o += " (expected ";
    append_spaced_hex(o, check_wire_bytes(f.dialect, f.check.expected));
    o += ')';
  }
  static void append_values(std::string& o, const SessionFrame& f) {
    for (std::size_t i = 0; i < f.values.size(); ++i) {
      o += i == 0 ? "  " : ", ";
      append_value_words(o, f.values[i], f.dialect);
    }
  }
  static void append_wait(std::string& o, const EventContext& c, const SessionTimeout& t) {
    switch (t.kind) {
      case UnansweredKind::InputEnded:
        o += "the input ended before its timeout";
        return;
      case UnansweredKind::AfterLoss:
        o += "no reply seen; capture data was lost meanwhile";
        return;
      case UnansweredKind::DamagedRequest:
        o += "the request had a bad check: the slave rightly ignored it";
        return;
      case UnansweredKind::Timeout:
        break;
    }
    if (t.timeout.reason == TimeoutReason::NextRequestFirst) {
      o += "no reply before the next request";
    } else if (t.timeout.reason == TimeoutReason::CarrierNoReply) {
      o += "no reply on the bus: " + solarman_v5::no_reply_reason(t.timeout.carrier_code);
    } else {
      o += "no reply";
    }
    if (c.has_timestamps) {
      o += " within ";
      append_fixed(o, t.timeout.waited * 1e3, 0);
      o += " ms";
    }
  }

  OutputStream& out_;
  std::vector<std::string> issues_;
};

}  // namespace

std::unique_ptr<EventWriter> make_text_event_writer(OutputStream& out) {
  return std::make_unique<TextEventWriter>(out);
}

}  // namespace pvtap::analyzer
