// FrameRecord: what the first pass learned about one frame, kept for every later pass.
#pragma once

#include <cstdint>
#include <type_traits>

#include "pvtap/codec/dialect.h"
#include "pvtap/matching/match_events.h"
#include "pvtap/session/bus_session.h"

namespace pvtap::dissector {

// PacketTime: a packet's capture time, as Wireshark's nstime_t holds it.
struct PacketTime {
  std::int64_t secs = 0;
  std::int32_t nsecs = 0;
};

// Lives in wmem file scope, which frees memory without running destructors.
struct FrameRecord {
  std::uint32_t packet = 0;        // the packet that shows the frame (0 until it is shown)
  std::uint32_t announced_in = 0;  // requests: the packet that showed their timeout (0: none)
  PacketTime time;                 // that packet's capture time
  Dialect dialect = kDefaultDialect;
  Role role = Role::Request;  // after the matcher's correction of GSL write echoes
  std::uint8_t station = 0;
  std::uint8_t function = 0;
  bool matched = false;  // the session paired it (its header could be read)
  bool check_ok = true;
  bool carried = false;  // no check on the wire: TCP carried it whole (Modbus/TCP)
  bool role_corrected = false;
  bool timed_out = false;
  bool unsolicited = false;
  bool duplicate = false;
  bool address_conflict = false;  // a second reply with other contents (SessionFrame)
  bool echo = false;              // the tap's adapter repeating `echo_of` (SessionFrame)
  bool count_mismatch = false;
  bool has_latency = false;
  bool values_trusted = false;  // a good check: its values may be decoded
  TimeoutReason timeout_reason = TimeoutReason::NoReply;
  UnansweredKind unanswered = UnansweredKind::Timeout;
  double latency = 0;  // replies: seconds from the request's end to the reply's start
  CountUnit count_unit = CountUnit::Bytes;
  std::uint16_t count_expected = 0;
  std::uint16_t count_found = 0;
  bool quantity_problem = false;       // requests: a quantity out of the specification's range
  bool broadcast_not_allowed = false;  // requests: to address 0, which only writes may use
  bool write_count_problem = false;    // writes: the byte count disagrees with the quantity
  std::uint16_t write_count_expected = 0;
  bool quantity_write_part = false;
  std::uint16_t quantity_found = 0;
  std::uint16_t quantity_min = 0;
  std::uint16_t quantity_max = 0;
  bool dialect_changed = false;  // its station spoke `previous_dialect` until this frame
  Dialect previous_dialect = kDefaultDialect;
  const char* station_name = nullptr;   // what the station said of itself, as known at this frame
  FrameRecord* request = nullptr;       // replies: the request answered (or answered before)
  FrameRecord* response = nullptr;      // requests: the first reply
  FrameRecord* late_for = nullptr;      // unsolicited replies: a request that timed out
  FrameRecord* next_request = nullptr;  // requests given up for the next one to the station
  FrameRecord* placed_by = nullptr;     // the request whose start places a reply's words
  FrameRecord* echo_of = nullptr;       // echoes: the request they repeat
  const std::uint8_t* bytes = nullptr;  // requests: their bytes, to decode their replies
  std::uint16_t length = 0;
};

static_assert(std::is_trivially_destructible_v<FrameRecord>);

}  // namespace pvtap::dissector
