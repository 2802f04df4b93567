// BusPlan: a scripted conversation on one bus, with the report pvtap audit must give for it.
// Captures of every kind are rendered from a plan, so each one's expected content is known.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "pvtap/codec/frame.h"
#include "pvtap/framing/stream_reassembler.h"
#include "pvtap/pcap/packet_builder.h"

namespace pvtap::forge {

using Bytes = std::vector<std::uint8_t>;

// BusItem: one transmission on the bus, in time order.
struct BusItem {
  double start = 0;  // the first byte begins
  double end = 0;    // the last byte ends
  Direction direction = Direction::ToSlave;
  Bytes bytes;
  bool is_frame = true;  // false: noise
  Role role = Role::Request;
  Dialect dialect = Dialect::Gsl;
  std::uint8_t station = 0;
  bool check_ok = true;
  bool exception = false;                   // a GSL exception or Hybrid error reply
  std::optional<std::size_t> request_item;  // for replies: the request they answer
};

// ExpectedFrame: one frame line pvtap audit must print (jsonl), in order.
struct ExpectedFrame {
  std::string raw_hex;
  Role role = Role::Request;
  bool check_ok = true;
};

// ExpectedValue: a register value the summary must list for a station.
struct ExpectedValue {
  std::string station;  // key in the summary's "stations"
  std::string register_text;
  double value = 0;
};

// Expected: the audit a capture must give.
struct Expected {
  std::map<std::string, std::uint64_t> counts;  // summary keys: frames, timeouts, ...
  std::vector<ExpectedFrame> frames;
  std::vector<ExpectedValue> values;
  std::vector<std::string> args;  // extra pvtap audit arguments the capture needs
  bool ordered = true;            // frames must come in exactly this order
};

class BusPlan {
 public:
  explicit BusPlan(std::uint32_t baud = 9600) : char_time_(10.0 / baud) {}

  // A request starting at `at`, answered (when `reply` is set) `latency` seconds after its
  // end. Returns when the exchange is over on the bus. `corrupt_reply` flips one data byte.
  double exchange(double at, const Frame& request, const std::optional<Frame>& reply,
                  double latency, bool corrupt_reply = false);
  // The same with the reply's start given (for requests sent back to back).
  double exchange_at(double request_start, const Frame& request, double reply_start,
                     const std::optional<Frame>& reply, bool corrupt_reply = false);
  double noise(double at, Bytes bytes, Direction d = Direction::FromSlave);

  const std::vector<BusItem>& items() const { return items_; }
  // The first item from `from` on that is a frame of this dialect, role and station.
  std::size_t find(std::size_t from, Dialect d, Role r, std::uint8_t station) const;
  double char_time() const { return char_time_; }
  double end_time() const;

  // The audit of a capture that holds the whole plan, bytes lost at the listed stream ranges
  // excepted (per direction; serial renderers use Direction::Unknown for the one stream).
  struct LostRange {
    Direction direction = Direction::Unknown;
    std::uint64_t begin = 0;
    std::uint64_t end = 0;
  };
  // Frames of dialects outside `recognized` (--dialect) count as noise.
  Expected expected(const std::vector<LostRange>& lost = {},
                    DialectSet recognized = DialectSet::all()) const;
  // Stream offset of every item in its direction's stream (or in the one bus stream).
  std::vector<std::uint64_t> stream_offsets(bool per_direction) const;

  void expect_value(std::string station, std::string register_text, double value) {
    values_.push_back(ExpectedValue{std::move(station), std::move(register_text), value});
  }

 private:
  std::size_t add(double start, Direction d, Bytes bytes);
  std::vector<std::uint64_t> lost_bytes_per_item(const std::vector<LostRange>& lost) const;
  void count_item(std::size_t i, const std::vector<std::uint64_t>& lost_in, DialectSet recognized,
                  std::vector<bool>& answered, Expected& e) const;

  double char_time_;
  std::vector<BusItem> items_;
  std::vector<ExpectedValue> values_;
};

std::string hex_of(const Bytes& bytes);

}  // namespace pvtap::forge
