#include "bus/bus_master.h"

#include <algorithm>
#include <array>

#include "bus/frame_shapes.h"
#include "dialects/inverter_dialect.h"
#include "faults/frame_damage.h"

namespace pvtap::sim {
namespace {

constexpr Micros ms(double v) {
  return static_cast<Micros>(v * 1000.0);
}

// The event as the line left it: its check bad, its values untrustworthy, and what a reader
// can still make of its bytes.
void mark_damaged(BusEvent& event, const FrameDamage& damage, FaultKind kind) {
  event.fault = std::string(to_string(kind));
  event.check_ok = false;
  event.values.clear();  // a frame with a bad check carries no trustworthy values
  if (damage.reading == DamageReading::Noise) {
    event.kind = BusEvent::Kind::Noise;
    return;
  }
  event.station = wire_station(event.bytes, event.dialect);
  event.function = wire_function(event.bytes, event.dialect);
}

}  // namespace

BusMaster::BusMaster(const SimConfig& config)
    : config_(config),
      random_(config.seed),
      second_random_(config.seed ^ 0x5EC0'0D0Bull),
      wire_(config.baud, config.echo) {
  for (unsigned i = 0; i < config.inverters; ++i) {
    const auto station = static_cast<std::uint8_t>(config.first_station + i);
    const Dialect d = config.dialects[i % config.dialects.size()];
    inverters_.emplace_back(station, d, config.seed, config.start);
    // Another plant with the same address: other values in every register.
    if (config.address_conflict == station)
      impostor_.emplace(station, d, config.seed ^ 0xC0'4F11C7ull, config.start);
  }
  add_devices();
}

std::optional<FaultKind> BusMaster::pick_fault(Dialect d) {
  if (closing_) return std::nullopt;
  for (unsigned k = 0; k < kFaultKinds; ++k) {
    const auto kind = static_cast<FaultKind>(k);
    if (!config_.faults.drawn(kind)) continue;
    if (random_.percent(config_.faults[kind])) {
      // A dialect without error replies (ASCII) has silence as its only error path.
      const InverterDialect* inverter = inverter_dialect(d);
      if (kind == FaultKind::ErrorReply && inverter != nullptr && inverter->errors_are_silence) {
        return FaultKind::Missing;
      }
      return kind;
    }
  }
  return std::nullopt;
}

std::optional<FaultKind> BusMaster::placed(std::optional<FaultKind> fault) const {
  // A request that pins the end of a damaged reply must itself be good.
  if (fault == FaultKind::CorruptRequest &&
      (next_request_pins_ || !wire_.may_damage(Role::Request)))
    return std::nullopt;
  const bool damages_reply = fault == FaultKind::Corrupt || fault == FaultKind::CorruptData;
  if (damages_reply && !wire_.may_damage(Role::Response)) return std::nullopt;
  return fault;
}

Micros BusMaster::timeout_after(Micros request_end) {
  return request_end + ms(config_.timeout_s * 1000.0) + random_.between(20, 40) * 1000;
}

Micros BusMaster::send_damaged_requests(const Frame& request, Micros at) {
  for (unsigned sent = 1;; ++sent) {
    BusEvent req = frame_event(request);
    const FrameDamage damage = damage_frame(req.bytes, request.dialect, Role::Request, random_);
    mark_damaged(req, damage, FaultKind::CorruptRequest);
    const std::uint8_t station = req.station, function = req.function;
    const Micros end = wire_.put(std::move(req), at);
    timeline_.faults.push_back(
        {end, request.station, std::string(to_string(FaultKind::CorruptRequest))});
    // An ASCII request damaged into noise is no request at all to a reader.
    if (damage.reading == DamageReading::BadCheckFrame)
      timeline_.unanswered_damaged_requests.push_back({at, end, station, function, {}});
    at = timeout_after(end);
    if (sent == kMaxDamagedRun || !random_.percent(kDamagedRetryPercent) ||
        !wire_.may_damage(Role::Request))
      return at;
  }
}

Micros BusMaster::poll(Inverter& inv, const PollBlock& block, Micros at) {
  const std::optional<FaultKind> fault = placed(pick_fault(inv.dialect()));
  next_request_pins_ = false;
  const Frame request = read_request(inv.dialect(), inv.station(), block);
  if (fault == FaultKind::CorruptRequest) return send_damaged_requests(request, at);
  const Micros request_end = wire_.put(frame_event(request), at);
  if (fault)
    timeline_.faults.push_back({request_end, inv.station(), std::string(to_string(*fault))});
  if (fault == FaultKind::Missing) {
    timeline_.timeouts.push_back({at, request_end, inv.station(), block.function, {}});
    return timeout_after(request_end);
  }
  BusEvent rep = inv.reply(block, fault, request_end, random_);
  const Micros free =
      answer(std::move(rep), fault, {at, request_end, inv.station(), block.function, {}});
  if (fault || !impostor_ || impostor_->station() != inv.station()) return free;
  return conflicting_reply(block, request_end, free, random_, kTurnaroundMinMs, kTurnaroundMaxMs);
}

Micros BusMaster::answer(BusEvent rep, std::optional<FaultKind> fault, TimeoutTruth request) {
  std::optional<FrameDamage> damage;
  if (fault == FaultKind::Corrupt) {
    damage = damage_frame(rep.bytes, rep.dialect, Role::Response, random_);
    mark_damaged(rep, *damage, FaultKind::Corrupt);
  } else if (fault == FaultKind::CorruptData) {
    damage = damage_reply_data(rep.bytes, rep.dialect, random_);
    mark_damaged(rep, *damage, FaultKind::CorruptData);
  }
  // A slow reply still comes inside the master's timeout: late, not lost.
  const auto slow_max =
      std::clamp<std::int64_t>(ms(config_.timeout_s * 1000.0) / 1000 - 50, 61, 800);
  rep.latency = fault == FaultKind::Slow
                    ? random_.between(std::min<std::int64_t>(300, slow_max), slow_max) * 1000
                    : random_.between(15, 60) * 1000;
  BusEvent copy = rep;
  Micros end = wire_.put(std::move(rep), request.request_end + copy.latency);
  if (damage && damage->reading == DamageReading::Noise) {
    // No reply a reader can see: the request timed out, and the master waited it out.
    timeline_.timeouts.push_back(request);
    return std::max(end, timeout_after(request.request_end));
  }
  // A damaged reply is pinned at its end by a silence no carrier can miss, or (its length
  // intact in its header) by the next request, sent soon after as a busy master does.
  if (fault == FaultKind::CorruptData) {
    next_request_pins_ = true;
    return end + random_.between(kCloseRequestMs, kCloseRequestMs + 7) * 1000;
  }
  if (damage) return end + random_.between(kPinningPauseMs, kPinningPauseMs + 60) * 1000;
  if (fault == FaultKind::Duplicate) {
    const Micros gap = random_.between(8, 15) * 1000;
    copy.latency = end + gap - request.request_end;
    copy.fault = std::string(to_string(FaultKind::Duplicate));
    end = wire_.put(std::move(copy), end + gap);
  }
  if (fault == FaultKind::Noise)
    end = wire_.put_noise(end + random_.between(8, 20) * 1000, random_);
  return end + random_.between(20, 60) * 1000;
}

void BusMaster::set_aside_unexpired_timeouts() {
  if (wire_.events().empty()) return;
  const Micros last = wire_.events().back().end;
  const Micros wait = ms(config_.timeout_s * 1000.0);
  auto& pending = timeline_.timeouts;
  while (!pending.empty() && pending.back().request_end + wait > last) {
    timeline_.unanswered_at_end.insert(timeline_.unanswered_at_end.begin(), pending.back());
    pending.pop_back();
  }
}

// A capture that ends on a damaged request would leave a reader to guess whether its slave
// ignored it or had no time to answer: the master polls once more, without faults.
void BusMaster::close_on_a_good_frame(Micros at) {
  const auto& events = wire_.events();
  if (events.empty() || events.back().kind != BusEvent::Kind::Frame ||
      events.back().role != Role::Request || events.back().check_ok)
    return;
  closing_ = true;
  if (inverters_.empty()) {
    poll_device(*devices_.front(), devices_.front()->requests(1).front(), at);
    return;
  }
  Inverter& inv = inverters_.front();
  for (const PollBlock& block : poll_blocks(inv.dialect())) {
    if (block.first_round_only) continue;
    poll(inv, block, at);
    return;
  }
}

std::vector<BusMaster::PollStep> BusMaster::round_steps(const PollCursor& cursor) {
  if (cursor.master != 1) return second_round_steps();
  std::vector<PollStep> steps;
  for (Inverter& inv : inverters_)
    for (const PollBlock& block : poll_blocks(inv.dialect()))
      if (!block.first_round_only || cursor.round == 0) steps.push_back({&inv, block, nullptr, {}});
  for (auto& device : devices_)
    for (const Frame& request : device->requests(cursor.round))
      steps.push_back({nullptr, {}, device.get(), request});
  return steps;
}

void BusMaster::begin_round(PollCursor& c, Micros stop) {
  while (!c.done && c.next == c.steps.size()) {
    if (c.next > 0 || c.round > 0) {
      c.round_start = std::max(c.round_start + ms(c.period_s * 1000.0), c.at);
      ++c.round;
    }
    if (c.round_start >= stop) {
      c.done = true;
      return;
    }
    SimRandom& random = c.master == 1 ? random_ : second_random_;
    c.at = c.round_start + random.between(0, 30) * 1000;  // the logger's own jitter
    c.steps = round_steps(c);
    c.next = 0;
  }
}

Micros BusMaster::poll_step(const PollCursor& c) {
  const PollStep& step = c.steps[c.next];
  if (c.master != 1) return second_poll(*step.inverter, step.block, c.at);
  if (step.device) return poll_device(*step.device, step.request, c.at);
  return poll(*step.inverter, step.block, c.at);
}

BusTimeline BusMaster::run() {
  const Micros stop = config_.start + ms(config_.duration_s * 1000.0);
  std::array<PollCursor, 2> cursors;
  cursors[0].period_s = config_.period_s;
  cursors[0].round_start = config_.start;
  begin_round(cursors[0], stop);
  cursors[1].master = 2;
  cursors[1].done = config_.masters < 2 || inverters_.empty();
  cursors[1].period_s = config_.second_period_s > 0 ? config_.second_period_s
                                                    : config_.period_s * kSecondPeriodFactor;
  cursors[1].round_start = config_.start + second_random_.between(100, 700) * 1000;
  if (!cursors[1].done) begin_round(cursors[1], stop);
  while (!cursors[0].done || !cursors[1].done) {
    // The master whose next request comes first sends it, whatever the line carries then.
    const bool second = !cursors[1].done && (cursors[0].done || cursors[1].at < cursors[0].at);
    PollCursor& c = cursors[second ? 1 : 0];
    const std::size_t first = wire_.events().size();
    wire_.begin_exchange(c.master);
    Micros free = poll_step(c);
    if (config_.masters > 1) free = settle_collision(first, free, cursors[second ? 0 : 1]);
    c.at = free;
    ++c.next;
    begin_round(c, stop);
  }
  if (config_.masters > 1) wire_.sort_by_time();
  close_on_a_good_frame(cursors[0].round_start);  // the next round's first poll
  set_aside_unexpired_timeouts();
  describe_shared_bus();
  timeline_.events = wire_.take_events();
  for (const auto& device : devices_)
    timeline_.devices.push_back({device->station(), device->label(), device->layout()});
  return std::move(timeline_);
}

}  // namespace pvtap::sim
