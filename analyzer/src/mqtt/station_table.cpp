// StationTable: recording replies, judging blocks and stations.
#include "mqtt/station_table.h"

#include <algorithm>

#include "mqtt/mqtt_payloads.h"
#include "mqtt/mqtt_topics.h"
#include "pvtap/codec/device_identification.h"

namespace pvtap::analyzer {
namespace {

constexpr std::string_view kIdentityKeys[] = {"model_name", "manufacturer_name", "serial_number",
                                              "device_number", "firmware_version"};

// A reply with a good check and values (an error reply may carry the Hybrid device number).
bool is_good_reply(const SessionFrame& f) {
  return f.frame != nullptr && f.role == Role::Response && f.values_trusted && !f.values.empty();
}

// A device identification reply names the device on its Home Assistant card.
void note_identification(StationState& s, const SessionFrame& f) {
  const auto id = read_device_identification(*f.frame);
  if (!id) return;
  const std::pair<std::string*, std::string_view> parts[] = {{&s.device.vendor, id->vendor()},
                                                             {&s.device.product, id->product()},
                                                             {&s.device.revision, id->revision()}};
  for (const auto& [kept, said] : parts) {
    if (said.empty() || *kept == said) continue;
    kept->assign(said);
    s.identity_changed = true;
  }
}

void touch_block(StationState& s, const SessionFrame& f) {
  if (f.decode.status != DecodeStatus::Decoded) return;
  s.blocks[{f.frame->function, f.decode.start}].seen(f.start_time);
}

}  // namespace

void PollBlock::seen(double time) {
  if (last > 0 && time > last) {
    intervals[next] = time - last;
    next = (next + 1) % kIntervals;
    if (count < kIntervals) ++count;
  }
  last = time;
}

std::optional<double> PollBlock::period() const {
  if (count < kIntervalsToJudge) return std::nullopt;
  std::array<double, kIntervals> sorted = intervals;
  const auto middle = sorted.begin() + static_cast<std::ptrdiff_t>(count / 2);
  std::nth_element(sorted.begin(), middle, sorted.begin() + static_cast<std::ptrdiff_t>(count));
  return *middle;
}

bool PollBlock::missing(double now) const {
  const std::optional<double> p = period();
  return p && now - last > 3 * *p;
}

bool is_identity_key(std::string_view key) {
  return std::find(std::begin(kIdentityKeys), std::end(kIdentityKeys), key) !=
         std::end(kIdentityKeys);
}

std::optional<double> StationState::period() const {
  std::optional<double> shortest;
  for (const auto& [id, block] : blocks) {
    const std::optional<double> p = block.period();
    if (p && (!shortest || *p < *shortest)) shortest = p;
  }
  return shortest;
}

bool StationState::answering(double now) const {
  // A master polling many times a second can pause for longer than three rounds without any
  // station being away (it, or the host reading the tap, was scheduled out).
  constexpr double kShortestOutage = 1.0;
  const std::optional<double> p = period();
  return !p || now - last_reply <= std::max(3 * *p, kShortestOutage);
}

void StationTable::record(const SessionFrame& f) {
  const bool identification = f.frame != nullptr && f.role == Role::Response && f.check.ok &&
                              f.station && modbus_family(f.dialect);
  if (identification) {
    StationState& s = stations_[*f.station];
    s.address = *f.station;
    s.dialect = f.dialect;
    note_identification(s, f);
  }
  if (!is_good_reply(f) || !f.station) return;
  StationState& s = stations_[*f.station];
  s.address = *f.station;
  s.dialect = f.dialect;
  s.last_reply = std::max(s.last_reply, f.start_time);
  s.replied_since_state = true;
  touch_block(s, f);
  std::string payload;
  const RegisterTable unmapped =
      f.frame != nullptr ? unmapped_table(f.dialect, f.frame->function) : RegisterTable::Registers;
  for (const DecodedValue& v : f.values) {
    if (!v.complete() || (v.def == nullptr && !raw_)) continue;
    const std::string key =
        v.def != nullptr ? value_key(v) : std::string(unmapped_key(unmapped, v.address).view());
    auto it = s.values.find(key);
    if (it == s.values.end()) it = s.values.emplace(key, HeldValue{}).first;
    HeldValue& held = it->second;
    if (v.def != nullptr && is_identity_key(v.def->key)) {
      payload.clear();
      append_value_payload(payload, v);
      const bool first = held.time == 0;
      std::string before;
      if (!first) append_value_payload(before, held.value);
      if (first || before != payload) s.identity_changed = true;
    }
    held.value = v;
    held.time = f.start_time;
  }
}

std::size_t StationTable::blocks() const {
  std::size_t n = 0;
  for (const auto& [address, s] : stations_) n += s.blocks.size();
  return n;
}

std::size_t StationTable::blocks_missing(double now) const {
  std::size_t n = 0;
  for (const auto& [address, s] : stations_) {
    for (const auto& [id, block] : s.blocks)
      if (block.missing(now)) ++n;
  }
  return n;
}

}  // namespace pvtap::analyzer
