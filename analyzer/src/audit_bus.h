// AuditRun's bus: one BusSession and the sink that passes its events on to the run.
#pragma once

#include <string>

#include "audit_run.h"

namespace pvtap::analyzer {

// BusOutput: the sink of one bus session; it tags events with the bus they came from.
class AuditRun::BusOutput : public BusSessionSink {
 public:
  BusOutput(AuditRun& run, std::string name, bool has_timestamps)
      : run_(run), name_(std::move(name)) {
    context_.bus = name_;
    context_.has_timestamps = has_timestamps;
  }
  void on_frame(const SessionFrame& f) override { run_.on_frame(context_, f); }
  void on_timeout(const SessionTimeout& t) override {
    if (t.kind == UnansweredKind::Timeout) ++run_.timeouts_seen_;
    if (run_.events_) run_.events_->timeout(context_, t);
    if (run_.mqtt_) run_.mqtt_->timeout(context_, t);
  }
  void on_noise(const SessionNoise& n) override { run_.on_noise(context_, n); }
  void on_gap(const SessionGap& g) override {
    if (run_.events_) run_.events_->gap(context_, g);
    if (run_.mqtt_) run_.mqtt_->gap(context_, g);
  }
  const std::string& name() const { return name_; }

 private:
  AuditRun& run_;
  std::string name_;
  EventContext context_;
};

struct AuditRun::Bus {
  Bus(AuditRun& run, const std::string& name, BusSessionOptions options,
      const RegisterDecoder& decoder)
      : output(run, name, options.has_timestamps), session(options, decoder, output) {}
  BusOutput output;
  BusSession session;
};

}  // namespace pvtap::analyzer
