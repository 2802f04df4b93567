#include "session/latest_readings.h"

#include <algorithm>
#include <utility>

namespace pvtap::detail {

std::optional<std::uint64_t> LatestReadings::key_of(const Frame& reply, const Frame* request) {
  // Without a start address the words cannot be placed (a Hybrid read reply alone would
  // only have the seed's default start, which is a guess).
  std::optional<std::uint16_t> start = reply.start;
  if (request != nullptr && request->start) start = request->start;
  if (!start) return std::nullopt;
  return std::uint64_t{reply.station} |
         (std::uint64_t{static_cast<std::uint8_t>(reply.dialect)} << 8) |
         (std::uint64_t{reply.function} << 16) | (std::uint64_t{*start} << 24);
}

void LatestReadings::store(const Frame& reply, const Frame* request, double time) {
  const std::optional<std::uint64_t> key = key_of(reply, request);
  if (!key) return;
  auto it = blocks_.find(*key);
  if (it == blocks_.end()) {
    if (blocks_.size() >= kMaxBlocks) return;
    it = blocks_.emplace(*key, Block{}).first;
  }
  Block& b = it->second;
  b.sequence = sequence_++;
  b.time = time;
  b.reply = reply;
  b.has_request = request != nullptr;
  if (request != nullptr) {
    b.request_function = request->function;
    b.request_start = request->start;
    b.request_count = request->count;
  }
}

Frame LatestReadings::request_of(const Block& b) {
  Frame r;
  r.dialect = b.reply.dialect;
  r.role = Role::Request;
  r.station = b.reply.station;
  r.function = b.request_function;
  r.start = b.request_start;
  r.count = b.request_count;
  return r;
}

std::map<std::uint8_t, StationReadings> LatestReadings::decode(
    const RegisterDecoder& decoder) const {
  std::vector<const Block*> order;
  order.reserve(blocks_.size());
  for (const auto& entry : blocks_) order.push_back(&entry.second);
  std::sort(order.begin(), order.end(),
            [](const Block* a, const Block* b) { return a->sequence < b->sequence; });

  // Newer blocks overwrite the values of older ones at the same address.
  using ValueKey = std::pair<std::uint8_t, std::uint16_t>;  // dialect, written address
  std::map<std::uint8_t, std::map<ValueKey, DecodedValue>> by_station;
  std::map<std::uint8_t, double> last_time;
  std::vector<DecodedValue> values;
  for (const Block* b : order) {
    values.clear();
    const Frame request = request_of(*b);
    decoder.decode(b->reply, b->has_request ? &request : nullptr, values);
    if (b->reply.dialect == Dialect::Hybrid && b->reply.device) {
      values.push_back(decoder.decode_device_number(*b->reply.device));
    }
    auto& table = by_station[b->reply.station];
    for (const DecodedValue& v : values) {
      if (v.def == nullptr || !v.complete()) continue;
      table[ValueKey{static_cast<std::uint8_t>(b->reply.dialect), v.address}] = v;
    }
    last_time[b->reply.station] = std::max(last_time[b->reply.station], b->time);
  }

  std::map<std::uint8_t, StationReadings> out;
  for (const auto& [station, table] : by_station) {
    StationReadings& r = out[station];
    r.last_time = last_time[station];
    r.values.reserve(table.size());
    for (const auto& [key, value] : table) {
      r.values.push_back(LatestValue{static_cast<Dialect>(key.first), value});
    }
  }
  return out;
}

}  // namespace pvtap::detail
