#include "gateway/solarman_v5_flow.h"

#include <string>

namespace pvtap::analyzer {

void SolarmanV5Flow::data(Direction d, std::span<const std::uint8_t> bytes, double time) {
  on_events(d, reader(d).feed(bytes), time);
}

void SolarmanV5Flow::gap(Direction d, std::uint64_t lost, double time) {
  on_events(d, reader(d).discontinuity(), time);
  if (bus_ != nullptr) bus_->data_lost(d, time, lost);
}

void SolarmanV5Flow::finish(double time) {
  for (Direction d : {Direction::ToSlave, Direction::FromSlave}) {
    on_events(d, reader(d).finish(), time);
  }
  if (bus_ == nullptr) return;
  bus_->end_turn(Direction::ToSlave);
  bus_->end_turn(Direction::FromSlave);
}

// Each RTU frame is whole (its V5 frame pins both ends): its turn ends with it. Broken V5
// frames and noise carry no frame the bus could trust; the reader counts them.
void SolarmanV5Flow::on_events(Direction d, std::span<const solarman_v5::Event> events,
                               double time) {
  for (const solarman_v5::Event& e : events) {
    if (e.kind != solarman_v5::Event::Kind::Frame || e.frame.rtu_length == 0) continue;
    BusSession& bus = bus_for(e.frame.header.serial);
    bus.feed(BusChunk{e.frame.rtu(), time, d});
    bus.end_turn(d);
  }
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

solarman_v5::Totals SolarmanV5Flow::totals() const {
  solarman_v5::Totals t = readers_[0].totals();
  t += readers_[1].totals();
  return t;
}

}  // namespace pvtap::analyzer
