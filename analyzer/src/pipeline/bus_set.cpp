#include "pipeline/bus_set.h"

#include "pvtap/session/event_tally.h"

namespace pvtap::analyzer {
namespace {

// BusOutput: the sink of one bus session; it tags the events with the bus they came from.
class BusOutput : public BusSessionSink {
 public:
  BusOutput(std::string name, bool has_timestamps, bool from_recording_start, EventWriter& events)
      : name_(std::move(name)), events_(events) {
    context_.bus = name_;
    context_.has_timestamps = has_timestamps;
    context_.from_recording_start = from_recording_start;
  }
  void on_frame(const SessionFrame& f) override { events_.frame(context_, f); }
  void on_timeout(const SessionTimeout& t) override { events_.timeout(context_, t); }
  void on_noise(const SessionNoise& n) override { events_.noise(context_, n); }
  void on_gap(const SessionGap& g) override { events_.gap(context_, g); }
  void on_collision(const SessionCollision& k) override { events_.collision(context_, k); }
  void on_line_error(const SessionLineError& e) override { events_.line_error(context_, e); }
  void on_driver_glitch(const SessionDriverGlitch& g) override {
    events_.driver_glitch(context_, g);
  }
  const std::string& name() const { return name_; }
  void attach(const BusSession& session) { context_.session = &session; }

 private:
  std::string name_;
  EventWriter& events_;
  EventContext context_;
};

}  // namespace

struct BusSet::Bus {
  Bus(const std::string& name, const BusSessionOptions& options, const RegisterDecoder& decoder,
      bool from_recording_start, EventWriter& events)
      : output(name, options.has_timestamps, from_recording_start, events),
        session(options, decoder, output) {
    output.attach(session);
  }
  BusOutput output;
  BusSession session;
};

BusSet::BusSet(const RegisterDecoder& decoder, EventWriter& events, bool from_recording_start)
    : decoder_(decoder), events_(events), from_recording_start_(from_recording_start) {}

BusSet::~BusSet() = default;

BusSession* BusSet::find(const std::string& name) {
  const auto it = by_name_.find(name);
  return it == by_name_.end() ? nullptr : &it->second->session;
}

const BusSession* BusSet::find(const std::string& name) const {
  const auto it = by_name_.find(name);
  return it == by_name_.end() ? nullptr : &it->second->session;
}

BusSession& BusSet::add(const std::string& name, const BusSessionOptions& options) {
  buses_.push_back(std::make_unique<Bus>(name, options, decoder_, from_recording_start_, events_));
  by_name_[name] = buses_.back().get();
  return buses_.back()->session;
}

BusSession& BusSet::find_or_add(const std::string& name, const BusSessionOptions& options) {
  if (BusSession* bus = find(name)) return *bus;
  return add(name, options);
}

void BusSet::idle(double now) {
  for (auto& bus : buses_) bus->session.idle(now);
}

void BusSet::finish() {
  for (auto& bus : buses_) bus->session.finish();
}

std::optional<double> BusSet::next_deadline() const {
  std::optional<double> earliest;
  for (const auto& bus : buses_) {
    const std::optional<double> due = bus->session.next_deadline();
    if (due && (!earliest || *due < *earliest)) earliest = due;
  }
  return earliest;
}

std::vector<BusFindings> BusSet::findings() const {
  std::vector<BusFindings> out;
  for (const auto& bus : buses_)
    out.push_back(BusFindings{bus->output.name(), bus->session.report(), std::nullopt});
  return out;
}

EventTally BusSet::tally() const {
  EventTally sum;
  for (const auto& bus : buses_) sum.merge(bus->session.tally());
  return sum;
}

EventCounts BusSet::counts() const {
  EventCounts sum;
  for (const auto& bus : buses_) sum += bus->session.tally().counts();
  return sum;
}

ReassemblerTotals BusSet::totals() const {
  ReassemblerTotals sum;
  for (const auto& bus : buses_) sum += bus->session.totals();
  return sum;
}

}  // namespace pvtap::analyzer
