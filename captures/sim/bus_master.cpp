#include "bus_master.h"

#include <algorithm>
#include <cmath>

#include "frame_shapes.h"
#include "plant_registers.h"
#include "pvtap/frame_codec.h"
#include "pvtap/function_codes.h"
#include "reply_corruption.h"

namespace pvtap::sim {
namespace {

constexpr Micros ms(double v) {
  return static_cast<Micros>(v * 1000.0);
}

DeviceNumber device_of(const RegisterImage& image) {
  const WordList w = image.block(0x1060, 2);
  return {static_cast<std::uint8_t>(w[0] >> 8),
          static_cast<std::uint32_t>((w[0] & 0xFF) << 16 | w[1])};
}

// The bus event of a frame, its bytes from the core's encoder.
BusEvent frame_event(const Frame& frame) {
  BusEvent e;
  e.bytes = encode_frame(frame);
  e.dialect = frame.dialect;
  e.role = frame.role;
  e.station = frame.station;
  e.function = frame.function;
  return e;
}

}  // namespace

BusMaster::BusMaster(const SimConfig& config) : config_(config), random_(config.seed) {
  for (unsigned i = 0; i < config.inverters; ++i) {
    const auto station = static_cast<std::uint8_t>(config.first_station + i);
    const Dialect d = config.dialects[i % config.dialects.size()];
    inverters_.push_back(
        {station, d, PlantModel(station, config.seed, config.start), RegisterImage(d)});
  }
}

Micros BusMaster::char_time(std::size_t bytes) const {
  // 10 bits per character: start, 8 data, stop.
  return static_cast<Micros>(std::llround(static_cast<double>(bytes) * 1e7 / config_.baud));
}

Micros BusMaster::put(BusEvent event, Micros at) {
  event.start = at;
  event.end = at + char_time(event.bytes.size());
  const Micros end = event.end;
  timeline_.events.push_back(std::move(event));
  return end;
}

Micros BusMaster::put_noise(Micros at) {
  BusEvent noise;
  noise.kind = BusEvent::Kind::Noise;
  noise.role = Role::Response;
  noise.fault = "noise";
  // High bytes (0xA0-0xFE): no function code, and above the stations of the usual buses,
  // so the noise is not mistaken for the start of a frame.
  const auto n = random_.between(3, 12);
  while (noise.bytes.size() < static_cast<std::size_t>(n)) {
    const auto b = static_cast<std::uint8_t>(random_.between(0xA0, 0xFE));
    noise.bytes.push_back(b);
  }
  return put(std::move(noise), at);
}

std::optional<FaultKind> BusMaster::pick_fault(Dialect d) {
  for (unsigned k = 0; k < kFaultKinds; ++k) {
    const auto kind = static_cast<FaultKind>(k);
    if (random_.percent(config_.faults[kind])) {
      // The ASCII dialect's only error path is silence.
      if (kind == FaultKind::ErrorReply && d == Dialect::Ascii) return FaultKind::Missing;
      return kind;
    }
  }
  return std::nullopt;
}

Micros BusMaster::poll(Inverter& inv, const PollBlock& block, Micros at) {
  const Frame request = read_request(inv.dialect, inv.station, block);
  BusEvent req = frame_event(request);
  const Micros request_end = put(std::move(req), at);
  const auto fault = pick_fault(inv.dialect);
  if (fault) timeline_.faults.push_back({request_end, inv.station, std::string(to_string(*fault))});
  if (fault == FaultKind::Missing) {
    timeline_.timeouts.push_back({at, request_end, inv.station, block.function});
    return request_end + ms(config_.timeout_s * 1000.0) + random_.between(20, 40) * 1000;
  }
  inv.plant.advance(request_end);
  fill_registers(inv.plant, inv.image, inv.dialect);
  PollBlock sent = block;
  if (fault == FaultKind::CountMismatch) sent.count = static_cast<std::uint16_t>(block.count - 1);
  Frame reply = fault == FaultKind::ErrorReply
                    ? error_reply(inv.dialect, inv.station, block, device_of(inv.image),
                                  random_.percent(50) ? 0x02 : 0x06)
                    : read_reply(inv.dialect, inv.station, block,
                                 inv.image.block(sent.start, sent.count), device_of(inv.image));
  BusEvent rep = frame_event(reply);
  // The first copy of a duplicated reply is an ordinary reply; the second is the fault.
  if (fault && fault != FaultKind::Duplicate) rep.fault = std::string(to_string(*fault));
  if (fault != FaultKind::ErrorReply) rep.values = inv.image.truth(sent.start, sent.count);
  if (fault == FaultKind::Corrupt) {
    corrupt_one_byte(rep.bytes, inv.dialect, random_);
    rep.check_ok = false;
    rep.values.clear();  // a frame with a bad check carries no trustworthy values
  }
  // A slow reply still comes inside the master's timeout: late, not lost.
  const auto slow_max =
      std::clamp<std::int64_t>(ms(config_.timeout_s * 1000.0) / 1000 - 50, 61, 800);
  const Micros latency =
      fault == FaultKind::Slow
          ? random_.between(std::min<std::int64_t>(300, slow_max), slow_max) * 1000
          : random_.between(15, 60) * 1000;
  rep.latency = latency;
  BusEvent copy = rep;
  Micros end = put(std::move(rep), request_end + latency);
  if (fault == FaultKind::Duplicate) {
    const Micros gap = random_.between(8, 15) * 1000;
    copy.latency = end + gap - request_end;
    copy.fault = std::string(to_string(FaultKind::Duplicate));
    end = put(std::move(copy), end + gap);
  }
  if (fault == FaultKind::Noise) end = put_noise(end + random_.between(8, 20) * 1000);
  return end + random_.between(20, 60) * 1000;
}

void BusMaster::set_aside_unexpired_timeouts() {
  if (timeline_.events.empty()) return;
  const Micros last = timeline_.events.back().end;
  const Micros wait = ms(config_.timeout_s * 1000.0);
  auto& pending = timeline_.timeouts;
  while (!pending.empty() && pending.back().request_end + wait > last) {
    timeline_.unanswered_at_end.insert(timeline_.unanswered_at_end.begin(), pending.back());
    pending.pop_back();
  }
}

BusTimeline BusMaster::run() {
  const Micros stop = config_.start + ms(config_.duration_s * 1000.0);
  Micros round_start = config_.start;
  for (unsigned round = 0; round_start < stop; ++round) {
    Micros at = round_start + random_.between(0, 30) * 1000;  // the logger's own jitter
    for (Inverter& inv : inverters_) {
      for (const PollBlock& block : poll_blocks(inv.dialect)) {
        if (block.first_round_only && round > 0) continue;
        at = poll(inv, block, at);
      }
    }
    round_start = std::max(round_start + ms(config_.period_s * 1000.0), at);
  }
  set_aside_unexpired_timeouts();
  return std::move(timeline_);
}

}  // namespace pvtap::sim
