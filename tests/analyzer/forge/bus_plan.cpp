#include "bus_plan.h"

#include <algorithm>

#include "pvtap/codec/frame_codec.h"
#include "pvtap/codec/function_codes.h"

namespace pvtap::forge {
namespace {

bool is_exception(const Frame& f) {
  return f.exception_code.has_value() ||
         (f.dialect == Dialect::Hybrid && f.function == fc::kHybridError);
}

// Flips a byte in the middle of a frame: the check fails, the length rules still hold.
void corrupt(Bytes& bytes) {
  bytes[bytes.size() / 2] ^= 0x5A;
}

std::uint64_t overlap(std::uint64_t a, std::uint64_t b, std::uint64_t c, std::uint64_t d) {
  const std::uint64_t lo = std::max(a, c);
  const std::uint64_t hi = std::min(b, d);
  return hi > lo ? hi - lo : 0;
}

}  // namespace

std::string hex_of(const Bytes& bytes) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string out;
  for (const std::uint8_t b : bytes) {
    out += kDigits[b >> 4];
    out += kDigits[b & 0xF];
  }
  return out;
}

std::size_t BusPlan::add(double start, Direction d, Bytes bytes) {
  BusItem item;
  item.start = start;
  item.end = start + static_cast<double>(bytes.size()) * char_time_;
  item.direction = d;
  item.bytes = std::move(bytes);
  items_.push_back(std::move(item));
  return items_.size() - 1;
}

double BusPlan::exchange(double at, const Frame& request, const std::optional<Frame>& reply,
                         double latency, bool corrupt_reply) {
  const double request_end = at + static_cast<double>(encode_frame(request).size()) * char_time_;
  return exchange_at(at, request, request_end + latency, reply, corrupt_reply);
}

double BusPlan::exchange_at(double request_start, const Frame& request, double reply_start,
                            const std::optional<Frame>& reply, bool corrupt_reply) {
  const std::size_t r = add(request_start, Direction::ToSlave, encode_frame(request));
  items_[r].role = Role::Request;
  items_[r].dialect = request.dialect;
  items_[r].station = request.station;
  if (!reply) return items_[r].end;
  Bytes bytes = encode_frame(*reply);
  if (corrupt_reply) corrupt(bytes);
  const std::size_t a = add(reply_start, Direction::FromSlave, std::move(bytes));
  items_[a].role = Role::Response;
  items_[a].dialect = reply->dialect;
  items_[a].station = reply->station;
  items_[a].check_ok = !corrupt_reply;
  items_[a].exception = is_exception(*reply);
  items_[a].request_item = r;
  return items_[a].end;
}

double BusPlan::noise(double at, Bytes bytes, Direction d) {
  const std::size_t n = add(at, d, std::move(bytes));
  items_[n].is_frame = false;
  return items_[n].end;
}

std::size_t BusPlan::find(std::size_t from, Dialect d, Role r, std::uint8_t station) const {
  for (std::size_t i = from; i < items_.size(); ++i) {
    const BusItem& item = items_[i];
    if (item.is_frame && item.dialect == d && item.role == r && item.station == station) return i;
  }
  return items_.size();
}

double BusPlan::end_time() const {
  double end = 0;
  for (const BusItem& item : items_) end = std::max(end, item.end);
  return end;
}

std::vector<std::uint64_t> BusPlan::stream_offsets(bool per_direction) const {
  std::vector<std::size_t> order(items_.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return items_[a].start < items_[b].start; });
  std::vector<std::uint64_t> offsets(items_.size());
  std::map<Direction, std::uint64_t> next;
  for (const std::size_t i : order) {
    const Direction d = per_direction ? items_[i].direction : Direction::Unknown;
    offsets[i] = next[d];
    next[d] += items_[i].bytes.size();
  }
  return offsets;
}

std::vector<std::uint64_t> BusPlan::lost_bytes_per_item(const std::vector<LostRange>& lost) const {
  const bool per_direction = std::any_of(lost.begin(), lost.end(), [](const LostRange& l) {
    return l.direction != Direction::Unknown;
  });
  const std::vector<std::uint64_t> offsets = stream_offsets(per_direction);
  std::vector<std::uint64_t> lost_in(items_.size(), 0);
  for (std::size_t i = 0; i < items_.size(); ++i) {
    const Direction d = per_direction ? items_[i].direction : Direction::Unknown;
    for (const LostRange& l : lost) {
      if (l.direction != d) continue;
      lost_in[i] += overlap(offsets[i], offsets[i] + items_[i].bytes.size(), l.begin, l.end);
    }
  }
  return lost_in;
}

Expected BusPlan::expected(const std::vector<LostRange>& lost, DialectSet recognized) const {
  const std::vector<std::uint64_t> lost_in = lost_bytes_per_item(lost);
  Expected e;
  auto& c = e.counts;
  for (const char* key :
       {"bytes", "frames", "requests", "responses", "bad_checks", "timeouts", "noise_bytes",
        "exceptions", "lost_bytes", "gaps", "unsolicited", "unanswered_after_loss"}) {
    c[key] = 0;
  }
  for (const LostRange& l : lost) {
    c["lost_bytes"] += l.end - l.begin;
    ++c["gaps"];
  }
  std::vector<bool> answered(items_.size(), false);
  std::vector<std::size_t> order(items_.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return items_[a].start < items_[b].start; });
  for (const std::size_t i : order) count_item(i, lost_in, recognized, answered, e);
  for (std::size_t i = 0; i < items_.size(); ++i) {
    const BusItem& item = items_[i];
    if (item.is_frame && item.role == Role::Request && lost_in[i] == 0 && !answered[i] &&
        recognized.contains(item.dialect)) {
      ++c["timeouts"];
    }
  }
  e.values = values_;
  return e;
}

// Counts one item as a frame or as noise; a damaged or unrecognized frame is noise.
void BusPlan::count_item(std::size_t i, const std::vector<std::uint64_t>& lost_in,
                         DialectSet recognized, std::vector<bool>& answered, Expected& e) const {
  const BusItem& item = items_[i];
  auto& c = e.counts;
  const std::uint64_t present = item.bytes.size() - lost_in[i];
  c["bytes"] += present;
  if (item.is_frame && !recognized.contains(item.dialect)) {
    c["noise_bytes"] += present;
    return;
  }
  if (!item.is_frame || lost_in[i] > 0) {
    c["noise_bytes"] += present;
    if (item.is_frame && item.request_item) {
      answered[*item.request_item] = true;
      if (lost_in[*item.request_item] == 0) ++c["unanswered_after_loss"];
    }
    return;
  }
  e.frames.push_back(ExpectedFrame{hex_of(item.bytes), item.role, item.check_ok});
  ++c["frames"];
  ++c[item.role == Role::Request ? "requests" : "responses"];
  if (!item.check_ok) ++c["bad_checks"];
  if (item.exception && item.check_ok) ++c["exceptions"];
  if (item.request_item) {
    answered[*item.request_item] = true;
    if (lost_in[*item.request_item] > 0) ++c["unsolicited"];
  }
}

}  // namespace pvtap::forge
