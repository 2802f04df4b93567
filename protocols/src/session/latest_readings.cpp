#include "session/latest_readings.h"

#include <algorithm>
#include <tuple>
#include <utility>

#include "pvtap/codec/function_codes.h"
#include "pvtap/registers/coil_bits.h"

namespace pvtap::detail {

std::optional<std::uint64_t> LatestReadings::key_of(const Frame& reply, const Frame* request) {
  // Without a start address the words cannot be placed (a Hybrid read reply alone would
  // only have the seed's default start, which is a guess).
  std::optional<std::uint16_t> start = reply.start;
  if (request != nullptr && request->start) start = request->start;
  if (!start) return std::nullopt;
  // A block is also its length: a shorter read at the same start keeps the longer one's
  // further words.
  std::uint64_t count = reply.words.size();
  if (request != nullptr && request->count) count = *request->count;
  return std::uint64_t{reply.station} |
         (std::uint64_t{static_cast<std::uint8_t>(reply.dialect)} << 8) |
         (std::uint64_t{reply.function} << 16) | (std::uint64_t{*start} << 24) |
         ((count & 0xFFFFu) << 40);
}

void LatestReadings::store(const Frame& reply, const Frame* request, double time) {
  const std::optional<std::uint64_t> key = key_of(reply, request);
  if (!key) return;
  auto it = blocks_.find(*key);
  if (it == blocks_.end()) {
    if (blocks_.size() >= kMaxBlocks) return;
    it = blocks_.emplace(*key, Block{}).first;
    if (infer_) it->second.inference = start_inference(reply, request);
  }
  Block& b = it->second;
  if (b.inference >= 0) {
    inference_[static_cast<std::size_t>(b.inference)].stats.add(reply.words.span());
  }
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

// A new block's words are decoded once: the runs no map names are inferred, the block's
// replies feed the statistics from now on. Bits and blocks without such words are not.
std::int32_t LatestReadings::start_inference(const Frame& reply, const Frame* request) {
  if (inference_.size() >= kMaxInferred || reply.words.size() < 1 ||
      is_bit_table(unmapped_table(reply.dialect, reply.function))) {
    return -1;
  }
  scratch_.clear();
  const DecodeReport decoded = decoder_.decode(reply, request, scratch_);
  if (decoded.status != DecodeStatus::Decoded) return -1;
  const unsigned step = address_step(reply.dialect);
  std::vector<std::pair<std::uint16_t, std::uint16_t>> runs;
  for (std::size_t k = decoded.first; k < decoded.first + decoded.count; ++k) {
    const DecodedValue& v = scratch_[k];
    if (v.def != nullptr) continue;
    const auto offset =
        static_cast<std::uint16_t>((v.wire_address - decoded.start) / step);  // wraps: not mapped
    if (offset >= reply.words.size()) continue;
    if (!runs.empty() && runs.back().first + runs.back().second == offset) {
      ++runs.back().second;
    } else {
      runs.emplace_back(offset, 1);
    }
  }
  if (runs.empty()) return -1;
  Inference inference{BlockInference(reply.words.size()),
                      std::move(runs),
                      reply.station,
                      reply.dialect,
                      reply.function,
                      decoded.start};
  inference_.push_back(std::move(inference));
  return static_cast<std::int32_t>(inference_.size() - 1);
}

std::map<std::uint8_t, std::vector<InferredBlock>> LatestReadings::inferred() const {
  std::map<std::uint8_t, std::vector<InferredBlock>> out;
  for (const Inference& in : inference_) {
    InferredBlock b;
    b.dialect = in.dialect;
    b.table = unmapped_table(in.dialect, in.function);
    b.function = in.function;
    b.start = in.start;
    b.count = static_cast<std::uint16_t>(in.stats.size());
    b.replies = in.stats.samples();
    for (const auto& [from, count] : in.runs) {
      std::vector<InferredValue> values = in.stats.infer(from, count);
      b.values.insert(b.values.end(), std::make_move_iterator(values.begin()),
                      std::make_move_iterator(values.end()));
    }
    out[in.station].push_back(std::move(b));
  }
  for (auto& [station, blocks] : out) {
    std::sort(blocks.begin(), blocks.end(), [](const InferredBlock& a, const InferredBlock& b) {
      return std::tie(a.table, a.start, a.count) < std::tie(b.table, b.start, b.count);
    });
  }
  return out;
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

}  // namespace pvtap::detail

namespace pvtap {

RegisterTable unmapped_table(Dialect d, std::uint8_t function) {
  if (!modbus_family(d)) return RegisterTable::Registers;
  switch (function) {
    case fc::kGslReadInput:
      return RegisterTable::Input;
    case fc::kReadCoils:
    case fc::kWriteSingleCoil:
    case fc::kWriteMultipleCoils:
      return RegisterTable::Coils;
    case fc::kReadDiscreteInputs:
      return RegisterTable::DiscreteInputs;
    default:
      return RegisterTable::Holding;
  }
}

UnmappedKey unmapped_key(RegisterTable t, std::uint16_t address) {
  static constexpr char kHex[] = "0123456789abcdef";
  const std::string_view prefix = t == RegisterTable::Coils            ? "coil_0x"
                                  : t == RegisterTable::DiscreteInputs ? "discrete_0x"
                                  : t == RegisterTable::Input          ? "input_reg_0x"
                                                                       : "reg_0x";
  UnmappedKey key;
  for (const char c : prefix) key.chars[key.length++] = c;
  for (unsigned shift = 16; shift > 0; shift -= 4)
    key.chars[key.length++] = kHex[(static_cast<unsigned>(address) >> (shift - 4)) & 0xFu];
  return key;
}

std::string_view table_name(RegisterTable t) {
  switch (t) {
    case RegisterTable::Holding:
      return "holding register";
    case RegisterTable::Input:
      return "input register";
    case RegisterTable::Coils:
      return "coil";
    case RegisterTable::DiscreteInputs:
      return "discrete input";
    case RegisterTable::Registers:
      break;
  }
  return "register";
}

std::uint8_t table_function(RegisterTable t) {
  switch (t) {
    case RegisterTable::Holding:
      return fc::kGslReadHolding;
    case RegisterTable::Input:
      return fc::kGslReadInput;
    case RegisterTable::Coils:
      return fc::kReadCoils;
    case RegisterTable::DiscreteInputs:
      return fc::kReadDiscreteInputs;
    case RegisterTable::Registers:
      break;
  }
  return 0;
}

bool is_bit_table(RegisterTable t) {
  return t == RegisterTable::Coils || t == RegisterTable::DiscreteInputs;
}

}  // namespace pvtap

namespace pvtap::detail {
namespace {

// Newer blocks overwrite the values of older ones at the same place: dialect, table (mapped
// values: Registers), written address.
using ValueKey = std::tuple<std::uint8_t, std::uint8_t, std::uint16_t>;

// The bits of a coils or discrete inputs reply as values of 0 or 1.
void add_bits(const Frame& reply, const Frame* request, const RegisterMap& map,
              std::map<ValueKey, LatestValue>& table) {
  const std::optional<CoilBits> bits = coil_bits(reply, request);
  if (!bits || !bits->start) return;
  const RegisterTable t = bits->inputs ? RegisterTable::DiscreteInputs : RegisterTable::Coils;
  for (std::size_t i = 0; i < bits->count; ++i) {
    const std::optional<std::uint16_t> address = bits->address(i);
    if (!address) break;
    LatestValue v;
    v.dialect = reply.dialect;
    v.table = t;
    v.coil = coil_def(map, *bits, i);
    v.value.address = *address;
    v.value.wire_address = *address;
    v.value.words_present = 1;
    v.value.raw = bits->on(i) ? 1u : 0u;
    v.value.value = v.value.raw;
    v.value.add(ValueWarning::NotInMap);
    table[ValueKey{static_cast<std::uint8_t>(reply.dialect), static_cast<std::uint8_t>(t),
                   *address}] = v;
  }
}

}  // namespace

std::map<std::uint8_t, StationReadings> LatestReadings::decode(
    const RegisterDecoder& decoder) const {
  std::vector<const Block*> order;
  order.reserve(blocks_.size());
  for (const auto& entry : blocks_) order.push_back(&entry.second);
  std::sort(order.begin(), order.end(),
            [](const Block* a, const Block* b) { return a->sequence < b->sequence; });

  std::map<std::uint8_t, std::map<ValueKey, LatestValue>> by_station;
  std::map<std::uint8_t, double> last_time;
  std::vector<DecodedValue> values;
  for (const Block* b : order) {
    values.clear();
    const Frame request = request_of(*b);
    const Frame* asked = b->has_request ? &request : nullptr;
    auto& table = by_station[b->reply.station];
    last_time[b->reply.station] = std::max(last_time[b->reply.station], b->time);
    const RegisterTable unmapped_table = pvtap::unmapped_table(b->reply.dialect, b->reply.function);
    if (is_bit_table(unmapped_table)) {
      const RegisterMap* own = decoder.station_map(b->reply.station);
      add_bits(b->reply, asked, own != nullptr ? *own : decoder.map(b->reply.dialect), table);
      continue;
    }
    decoder.decode(b->reply, asked, values);
    if (b->reply.device) {
      values.push_back(decoder.decode_device_number(*b->reply.device));
    }
    for (const DecodedValue& v : values) {
      // A value cut by the end of the block is shown where a later block has it whole.
      if (v.def != nullptr && !v.complete()) continue;
      if (v.def == nullptr && v.origin == ValueOrigin::DeviceHeader) continue;
      const RegisterTable t = v.def != nullptr ? RegisterTable::Registers : unmapped_table;
      LatestValue& slot = table[ValueKey{static_cast<std::uint8_t>(b->reply.dialect),
                                         static_cast<std::uint8_t>(t), v.address}];
      slot.dialect = b->reply.dialect;
      slot.table = t;
      slot.value = v;
    }
  }

  std::map<std::uint8_t, StationReadings> out;
  for (auto& [station, table] : by_station) {
    StationReadings& r = out[station];
    r.last_time = last_time[station];
    r.values.reserve(table.size());
    for (auto& [key, value] : table) r.values.push_back(value);
  }
  return out;
}

}  // namespace pvtap::detail
