#include "carriers/solarman_v5_flow.h"

#include <algorithm>
#include <cstdio>
#include <string>

namespace pvtap::analyzer {

namespace v5 = solarman_v5;

void SolarmanV5Flow::data(Direction d, std::span<const std::uint8_t> bytes, double time) {
  on_events(reader(d).feed(bytes), time);
}

void SolarmanV5Flow::gap(Direction d, std::uint64_t lost, double time) {
  on_events(reader(d).discontinuity(), time);
  if (bus_ != nullptr) bus_->data_lost(d, time, lost);
}

void SolarmanV5Flow::finish(double time) {
  for (Direction d : {Direction::ToSlave, Direction::FromSlave}) {
    on_events(reader(d).finish(), time);
  }
  pairing_.finish();
  if (bus_ == nullptr) return;
  bus_->end_turn(Direction::ToSlave);
  bus_->end_turn(Direction::FromSlave);
}

// Broken V5 frames and noise carry no frame the bus could trust; the reader counts them.
void SolarmanV5Flow::on_events(std::span<const v5::Event> events, double time) {
  for (const v5::Event& e : events) {
    if (e.kind == v5::Event::Kind::Frame) pairing_.frame(e.frame, time, e.offset);
  }
}

// Each RTU frame is whole (its V5 frame pins both ends): its turn ends with it. Requests go
// to the bus of the stick's serial (from its own frames), whatever serial they name.
void SolarmanV5Flow::release(const v5::Release& r) {
  switch (r.kind) {
    case v5::Release::Kind::Request:
      bus_for(pairing_.stick_serial().value_or(r.serial))
          .whole_frame(BusChunk{r.rtu, r.time, Direction::ToSlave});
      return;
    case v5::Release::Kind::Reply:
      bus_for(r.serial).whole_frame(BusChunk{r.rtu, r.time, Direction::FromSlave},
                                    r.answers_request);
      return;
    case v5::Release::Kind::NoReply:
      bus_for(r.serial).carrier_no_reply(r.time, r.code);
      return;
    case v5::Release::Kind::Refused:
      example(v5::describe_refusal(r.addressed_serial, r.serial));
      return;
    case v5::Release::Kind::Code: {
      char text[80];
      std::snprintf(text, sizeof text, "logger %u answered code %02x to sequence %02x", r.serial,
                    r.code, r.sequence);
      example(text);
      return;
    }
  }
}

// Each text once: a client with a wrong serial is refused request after request.
void SolarmanV5Flow::example(std::string text) {
  if (examples_.size() >= kMaxExamples) return;
  if (std::find(examples_.begin(), examples_.end(), text) != examples_.end()) return;
  examples_.push_back(std::move(text));
}

BusSession& SolarmanV5Flow::bus_for(std::uint32_t serial) {
  if (bus_ != nullptr && serial == serial_) return *bus_;
  serial_ = serial;
  bus_ = &buses_.logger_bus("v5:" + std::to_string(serial));
  // A new connection starts new streams: nothing of the previous one may join its bytes.
  bus_->restart(Direction::ToSlave);
  bus_->restart(Direction::FromSlave);
  return *bus_;
}

void SolarmanV5Flow::add_stats(NetworkStats& into) const {
  ++into.flows_analyzed;
  ++into.v5_flows;
  into.v5 += totals();
  std::vector<std::string>& said = into.v5_finding_examples;
  for (const std::string& e : examples_) {
    if (said.size() >= NetworkStats::kMaxExamples) break;
    // Each connection of a client with a wrong serial is refused alike: said once.
    if (std::find(said.begin(), said.end(), e) == said.end()) said.push_back(e);
  }
}

v5::Totals SolarmanV5Flow::totals() const {
  v5::Totals t = readers_[0].totals();
  t += readers_[1].totals();
  pairing_.add_counts(t);
  return t;
}

}  // namespace pvtap::analyzer
