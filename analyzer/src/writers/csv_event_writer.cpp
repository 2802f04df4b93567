// One CSV row per frame (and per timeout, noise run and gap, told apart by the type column),
// with a header row, quoted as RFC 4180 asks so that spreadsheets read it unchanged.
#include <string>
#include <vector>

#include "formatting/csv_text.h"
#include "formatting/number_text.h"
#include "report/frame_findings.h"
#include "writers/event_writers.h"

namespace pvtap::analyzer {
namespace {

constexpr std::string_view kHeader =
    "type,ts,bus,dialect,role,station,function,length,check,check_expected,latency_ms,raw,"
    "values,issues\n";

class CsvEventWriter : public EventWriter {
 public:
  explicit CsvEventWriter(OutputStream& out) : out_(out) {}

  void begin() override { out_.write(kHeader); }

  void frame(const EventContext& c, const SessionFrame& f) override {
    std::string& o = out_.buffer();
    begin_row(o, "frame", c, f.start_time);
    o += to_string(f.dialect);
    o += ',';
    o += to_string(f.role);
    o += ',';
    if (f.frame != nullptr) {
      append_uint(o, f.frame->station);
      o += ',';
      append_uint(o, f.frame->function);
    } else {
      o += ',';
    }
    o += ',';
    append_uint(o, f.bytes.size());
    o += f.check.carried ? ",tcp," : f.check.ok ? ",ok," : ",bad,";
    if (!f.check.ok) append_hex(o, check_wire_bytes(f.dialect, f.check.expected));
    o += ',';
    if (f.latency) append_fixed(o, *f.latency * 1e3, 3);
    o += ',';
    append_hex(o, f.bytes);
    o += ',';
    field_.clear();
    for (std::size_t i = 0; i < f.values.size(); ++i) {
      if (i > 0) field_ += "; ";
      append_value_words(field_, f.values[i], f.dialect);
    }
    append_csv_field(o, field_);
    o += ',';
    collect_issues(f, issues_);
    field_.clear();
    for (std::size_t i = 0; i < issues_.size(); ++i) {
      if (i > 0) field_ += "; ";
      field_ += issues_[i];
    }
    append_csv_field(o, field_);
    o += '\n';
    out_.done();
  }

  void timeout(const EventContext& c, const SessionTimeout& t) override {
    std::string& o = out_.buffer();
    begin_row(o, t.kind == UnansweredKind::Timeout ? "timeout" : "unanswered", c, t.time);
    o += to_string(t.timeout.dialect);
    o += ",request,";
    append_uint(o, t.timeout.station);
    o += ',';
    append_uint(o, t.timeout.function);
    o += ",,,,,,,";
    o += unanswered_reason(t);
    o += '\n';
    out_.done();
  }

  void noise(const EventContext& c, const SessionNoise& n) override {
    std::string& o = out_.buffer();
    begin_row(o, "noise", c, n.noise.start_time);
    o += ",,,,";
    append_uint(o, n.noise.bytes.size());
    o += ",,,,";
    append_hex(o, n.noise.bytes);
    o += ",,\n";
    out_.done();
  }

  void collision(const EventContext& c, const SessionCollision& k) override {
    std::string& o = out_.buffer();
    begin_row(o, "collision", c, k.start_time);
    o += ",,,,,,,,,,";
    o += "two transmissions at once (more than one master)";
    o += '\n';
    out_.done();
  }

  void gap(const EventContext& c, const SessionGap& g) override {
    std::string& o = out_.buffer();
    begin_row(o, "gap", c, g.time);
    o += ",,,,";
    if (g.lost_bytes) append_uint(o, *g.lost_bytes);
    o += ",,,,,,";
    o += g.lost_bytes ? "capture data lost" : "capture data lost (size unknown)";
    o += '\n';
    out_.done();
  }

 private:
  static void begin_row(std::string& o, std::string_view type, const EventContext& c, double time) {
    o += type;
    o += ',';
    if (c.has_timestamps) append_fixed(o, time, 6);
    o += ',';
    append_csv_field(o, c.bus);
    o += ',';
  }

  OutputStream& out_;
  std::string field_;
  std::vector<std::string> issues_;
};

}  // namespace

std::unique_ptr<EventWriter> make_csv_event_writer(OutputStream& out) {
  return std::make_unique<CsvEventWriter>(out);
}

}  // namespace pvtap::analyzer
