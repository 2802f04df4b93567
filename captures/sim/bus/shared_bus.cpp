// A shared bus: the second master's polls, the second device that answers to an inverter's
// address, and what a collision leaves of the two exchanges it met (the physics of a collision
// is in bus_wire.cpp).
//
// Who sends when: a master sends its next request when its own plan says, without listening
// to the line first (a logger assumes it owns the bus); within its own exchange it reads until
// the line falls silent, so a second reply to its request delays its next one. A slave answers
// a request it heard whole after its own latency, without listening first. The second device
// at a conflicting address is slower than the first by the first reply's length and 3-12 ms, so
// its reply follows the first one; where it meets another transmission, the two collide.
#include <algorithm>

#include "bus/bus_master.h"
#include "bus/frame_shapes.h"

namespace pvtap::sim {
namespace {

constexpr Micros kMs = 1000;

// The second master (a meter reader, a second logger) reads half of an inverter's measurement
// block: a block of its own on a station the first master polls too.
PollBlock second_master_block(const Inverter& inv) {
  PollBlock block = poll_blocks(inv.dialect()).back();
  block.count = static_cast<std::uint16_t>(std::max(1, block.count / 2));
  return block;
}

}  // namespace

std::vector<BusMaster::PollStep> BusMaster::second_round_steps() {
  std::vector<PollStep> steps;
  for (std::size_t i = 0; i < std::min<std::size_t>(2, inverters_.size()); ++i)
    steps.push_back({&inverters_[i], second_master_block(inverters_[i]), nullptr, {}});
  return steps;
}

Micros BusMaster::second_poll(Inverter& inv, const PollBlock& block, Micros at) {
  const Frame request = read_request(inv.dialect(), inv.station(), block);
  const Micros request_end = wire_.put(frame_event(request), at);
  BusEvent rep = inv.reply(block, std::nullopt, request_end, second_random_);
  rep.latency = second_random_.between(15, 60) * kMs;
  const Micros reply_at = request_end + rep.latency;
  const Micros end = wire_.put(std::move(rep), reply_at);
  const Micros free =
      end + second_random_.between(kSecondTurnaroundMinMs, kSecondTurnaroundMaxMs) * kMs;
  if (!impostor_ || impostor_->station() != inv.station()) return free;
  return conflicting_reply(block, request_end, free, second_random_, kSecondTurnaroundMinMs,
                           kSecondTurnaroundMaxMs);
}

Micros BusMaster::conflicting_reply(const PollBlock& block, Micros request_end, Micros free,
                                    SimRandom& random, std::int64_t turnaround_min_ms,
                                    std::int64_t turnaround_max_ms) {
  const Micros first_end = wire_.events().back().end;
  BusEvent rep = impostor_->reply(block, std::nullopt, request_end, random);
  const Micros at = first_end + random.between(3, 12) * kMs;
  rep.latency = at - request_end;
  rep.fault = "address_conflict";
  const Micros end = wire_.put(std::move(rep), at);
  return std::max(free, end + random.between(turnaround_min_ms, turnaround_max_ms) * kMs);
}

// The exchange a collision destroyed no longer has the fate its master's plan gave it: no
// timeout, no fault of its own (its request is lost in the collision).
void BusMaster::forget_truth_of(const DestroyedExchange& x, Micros request_end) {
  const auto same = [&](const TimeoutTruth& t) { return t.request_start == x.request_start; };
  std::erase_if(timeline_.timeouts, same);
  std::erase_if(timeline_.unanswered_damaged_requests, same);
  std::erase_if(timeline_.faults, [&](const FaultTruth& f) {
    return f.station == x.station && f.time >= x.request_start && f.time <= request_end;
  });
}

Micros BusMaster::settle_collision(std::size_t first, Micros free, PollCursor& other) {
  const std::optional<Overlap> hit = wire_.collide(first);
  if (!hit) return free;
  CollisionTruth truth{hit->start, hit->end, {}};
  const auto wait = static_cast<Micros>(config_.timeout_s * 1e6);
  Micros fresh_wait_until = free;
  for (const BusEvent* lost : {&hit->older, &hit->fresh}) {
    DestroyedExchange x;
    x.master = lost->master;
    Micros request_end = lost->end;
    if (lost->kind == BusEvent::Kind::Frame && lost->role == Role::Request) {
      x.request_lost = true;
      x.station = lost->station;
      x.function = lost->function;
      x.request_start = lost->start;
    } else {
      // Its request went out whole: the last one of its exchange before it.
      for (const BusEvent& e : wire_.events()) {
        if (e.exchange != lost->exchange || e.kind != BusEvent::Kind::Frame ||
            e.role != Role::Request || e.start >= lost->start || e.fault == "echo")
          continue;
        x.station = e.station;
        x.function = e.function;
        x.request_start = e.start;
        request_end = e.end;
      }
    }
    forget_truth_of(x, request_end);
    truth.destroyed.push_back(x);
    // The master heard no reply: it waits out its timeout, whenever it planned to go on.
    if (lost == &hit->older)
      other.at = std::max(other.at, request_end + wait);
    else
      fresh_wait_until = std::max(hit->end, request_end + wait);
  }
  timeline_.collisions.push_back(std::move(truth));
  return fresh_wait_until;
}

void BusMaster::describe_shared_bus() {
  for (const BusEvent& e : wire_.events())
    if (e.fault == "echo") ++timeline_.echoes;
  if (impostor_) {
    ConflictTruth conflict{impostor_->station(), 0};
    for (const BusEvent& e : wire_.events())
      if (e.fault == "address_conflict") ++conflict.second_replies;
    timeline_.conflicts.push_back(conflict);
  }
  if (config_.masters < 2) return;
  MasterTruth first{1, config_.period_s, kTurnaroundMinMs * kMs, kTurnaroundMaxMs * kMs, {}};
  for (const Inverter& inv : inverters_)
    for (const PollBlock& b : poll_blocks(inv.dialect()))
      if (!b.first_round_only) first.plan.push_back({inv.station(), b.function, b.start, b.count});
  for (const auto& device : devices_)
    for (const Frame& r : device->requests(1))
      first.plan.push_back({r.station, r.function, r.start.value_or(0), r.count.value_or(0)});
  timeline_.masters.push_back(std::move(first));
  MasterTruth second{2,
                     config_.second_period_s > 0 ? config_.second_period_s
                                                 : config_.period_s * kSecondPeriodFactor,
                     kSecondTurnaroundMinMs * kMs,
                     kSecondTurnaroundMaxMs * kMs,
                     {}};
  for (std::size_t i = 0; i < std::min<std::size_t>(2, inverters_.size()); ++i) {
    const PollBlock b = second_master_block(inverters_[i]);
    second.plan.push_back({inverters_[i].station(), b.function, b.start, b.count});
  }
  timeline_.masters.push_back(std::move(second));
}

}  // namespace pvtap::sim
