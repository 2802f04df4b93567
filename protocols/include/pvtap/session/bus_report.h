// What a BusSession found on one bus, ready for any presentation (text, JSON, a GUI).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "pvtap/codec/dialect.h"
#include "pvtap/codec/frame_codec.h"
#include "pvtap/framing/stream_reassembler.h"
#include "pvtap/matching/match_events.h"
#include "pvtap/registers/register_decoder.h"
#include "pvtap/registers/register_inference.h"
#include "pvtap/statistics/distribution_summary.h"
#include "pvtap/statistics/timing_statistics.h"

namespace pvtap {

// FrameExample: one frame kept as an example of a finding (its bytes copied).
struct FrameExample {
  std::uint64_t id = 0;
  double time = 0;  // start of the frame
  Dialect dialect = kDefaultDialect;
  Role role = Role::Request;
  std::uint8_t station = 0;
  std::uint8_t function = 0;
  FrameCheck check;
  std::vector<std::uint8_t> bytes;
};

// TimeoutExample: one request that got no reply.
struct TimeoutExample {
  Timeout timeout;
  double request_time = 0;  // start of the request
};

// ExceptionTally: how often a station refused a request with one error form.
//   GSL: code = the exception code; Hybrid: code = 0xFF (the 0xFF error reply).
struct ExceptionTally {
  Dialect dialect = kDefaultDialect;
  std::uint8_t code = 0;
  std::uint64_t count = 0;
};

// RoleCounts: frames of one dialect by role.
struct RoleCounts {
  std::uint64_t requests = 0;
  std::uint64_t responses = 0;
};

// RegisterTable: which of a device's four address spaces a value is of. Maps do not tell
// holding and input registers apart, so a mapped value is of `Registers`; a word no map covers
// is kept apart by the function that read it (Modbus family), or of `Registers` (the inverter
// dialects have one address space).
enum class RegisterTable : std::uint8_t {
  Registers,       // mapped registers, and the inverter dialects' words
  Holding,         // 0x03 (and the register writes, 0x17)
  Input,           // 0x04
  Coils,           // 0x01 (and 0x05, 0x0F)
  DiscreteInputs,  // 0x02
};

// "holding register", "input register", "coil", "discrete input", "register".
std::string_view table_name(RegisterTable t);
// The read function of a table (0x03, 0x04, 0x01, 0x02), 0 for Registers.
std::uint8_t table_function(RegisterTable t);
bool is_bit_table(RegisterTable t);
// The table of the words or bits a frame of `function` carries, when no map names them.
RegisterTable unmapped_table(Dialect d, std::uint8_t function);
// UnmappedKey: the key of an unmapped value, as a draft map names it, in a fixed buffer:
// "reg_0x0836" (holding registers, the inverter dialects' words), "input_reg_0x0002",
// "coil_0x0013", "discrete_0x0002".
struct UnmappedKey {
  std::array<char, 24> chars{};
  std::uint8_t length = 0;
  std::string_view view() const { return {chars.data(), length}; }
};
UnmappedKey unmapped_key(RegisterTable t, std::uint16_t address);

// LatestValue: the newest reading of one register and the dialect it was read in. A value no
// map names has a null value.def and its raw word (a bit of coils and discrete inputs: 0 or 1);
// `table` keeps such values of different address spaces apart.
struct LatestValue {
  Dialect dialect = kDefaultDialect;
  RegisterTable table = RegisterTable::Registers;
  DecodedValue value;
  const CoilDef* coil = nullptr;  // a bit the map names ([[coil]], [[discrete_input]])
  bool mapped() const { return value.def != nullptr || coil != nullptr; }
};

// InferredBlock: a polled block with words no map names, and what they probably hold
// (register_inference.h), from every good reply to it.
struct InferredBlock {
  Dialect dialect = kDefaultDialect;
  RegisterTable table = RegisterTable::Holding;
  std::uint8_t function = 0;  // of the replies
  std::uint16_t start = 0;    // wire address of the block's first word
  std::uint16_t count = 0;    // words
  std::uint32_t replies = 0;
  // The values of its unmapped runs; a value's first word is at start + offset (ASCII: two
  // addresses a word).
  std::vector<InferredValue> values;
};

// DeviceName: what a device said of itself (device identification objects 0-2, or the text of
// its report server ID reply); empty strings where it said nothing.
struct DeviceName {
  std::string vendor;
  std::string product;
  std::string revision;
  std::string server_id;  // from 0x11, when no identification named it
  bool empty() const {
    return vendor.empty() && product.empty() && revision.empty() && server_id.empty();
  }
  // "Vendor Product revision" or the server ID text.
  std::string text() const;
};

// StationSummary: everything counted for one station address.
struct StationSummary {
  std::uint8_t station = 0;
  std::array<RoleCounts, kDialectCount> by_dialect{};  // indexed by Dialect
  std::uint64_t requests = 0;
  std::uint64_t responses = 0;
  std::uint64_t bad_checks = 0;
  std::uint64_t timeouts = 0;         // good requests that got no reply
  std::uint64_t damaged_replies = 0;  // replies with a bad check to its requests
  std::uint64_t exceptions = 0;       // GSL exceptions and Hybrid error replies
  std::uint64_t unsolicited = 0;
  std::uint64_t duplicates = 0;
  std::uint64_t address_conflicts = 0;  // second replies that differ (SessionFrame)
  // Their mean time from the request's end to their start (with timestamps), seconds: the
  // second device's pattern beside the station's own `latency`.
  double address_conflict_latency = 0;
  std::uint64_t count_mismatches = 0;
  std::uint64_t dialect_changes = 0;
  DeviceName device;  // the newest identification the station gave
  DistributionSummary latency;
  double last_report_time = 0;  // when the newest value below arrived
  // The newest value of every register the station reported (read replies and write echoes
  // with good checks), sorted by dialect and address.
  std::vector<LatestValue> latest_values;
  // The blocks with unmapped words, sorted by table and start (BusSessionOptions::
  // infer_registers).
  std::vector<InferredBlock> inferred;
  // The SunSpec model chain its replies showed (RegisterDecoder learns it), when they did.
  std::optional<SunSpecChain> sunspec;
};

// ClaimedStation: an address that damaged frames of no station claimed, and how many did.
struct ClaimedStation {
  std::uint8_t station = 0;
  std::uint64_t frames = 0;
};

// UnknownStation: the damaged frames that no station can be named for (see station_rule.h):
// their station byte may be the damaged one. Noise is of no station either (BusCounters::bytes).
struct UnknownStation {
  std::uint64_t damaged_frames = 0;
  std::uint64_t unanswered_damaged_requests = 0;  // of them, requests no reply answered
  std::vector<ClaimedStation> claimed;            // sorted by address

  UnknownStation& operator+=(const UnknownStation& o);
};

// GapTally: capture data lost on the way to the analyzer.
struct GapTally {
  std::uint64_t gaps = 0;
  std::uint64_t lost_bytes = 0;  // sum of the gaps whose size is known
  std::uint64_t gaps_of_unknown_size = 0;
};

// LineErrorTally: what the UART reading a bus's line from its samples (a logic recording)
// could not read cleanly: characters with a framing or a parity error (drivers' glitches among
// them), breaks, and the bytes of drivers switching on or off.
struct LineErrorTally {
  std::uint64_t framing_errors = 0;
  std::uint64_t parity_errors = 0;
  std::uint64_t breaks = 0;
  std::uint64_t driver_glitches = 0;

  LineErrorTally& operator+=(const LineErrorTally& o);
};

// A bus whose poll cycles tell no second master still has one when this many requests went
// out while another request's reply was due (TimingReport::requests_while_reply_due), which
// one master never does: 0 on every bus of one master in the sample library and the real
// recordings, tens a minute on a shared bus. Collisions are counted on such a bus too.
inline constexpr std::uint64_t kSecondMasterRequests = 3;

// BusCounters: every counter of one bus, added up in one way (operator+=, which fails to
// compile when a counter is added here and not there).
struct BusCounters {
  ReassemblerTotals bytes;  // every direction added up
  std::uint64_t requests = 0;
  std::uint64_t responses = 0;
  std::array<RoleCounts, kDialectCount> by_dialect{};
  std::uint64_t malformed_frames = 0;  // found by structure but not parseable
  // Requests with a good check that got no reply: the slave did not answer.
  std::uint64_t timeouts = 0;
  std::array<std::uint64_t, 2> timeouts_by_reason{};  // NoReply, NextRequestFirst
  // Replies with a bad check that answered a request: the line damaged the answer.
  std::uint64_t damaged_replies = 0;
  // Requests with a bad check that got no reply: the slave rightly ignored them.
  std::uint64_t unanswered_damaged_requests = 0;
  std::uint64_t unanswered_at_end = 0;      // still within the timeout when the input ended
  std::uint64_t unanswered_after_loss = 0;  // the reply may be in lost capture data
  std::uint64_t transactions = 0;
  std::uint64_t unsolicited = 0;
  std::uint64_t late_replies = 0;  // unsolicited replies that fit a timed-out request
  std::uint64_t duplicates = 0;
  std::uint64_t address_conflicts = 0;  // second replies that differ (SessionFrame)
  std::uint64_t echoes = 0;             // requests the tap's adapter echoed (SessionFrame)
  // On a bus of two or more masters (kSecondMasterRequests): stretches of garbage where two
  // talked at once, and the requests whose reply was due while one happened (also among the
  // timeouts).
  std::uint64_t collisions = 0;
  std::uint64_t lost_in_collision = 0;
  std::uint64_t count_mismatches = 0;
  std::uint64_t role_corrections = 0;
  std::uint64_t dialect_changes = 0;       // a station's frames said it changed dialect
  std::uint64_t quantity_problems = 0;     // good requests asking for a quantity out of range
  std::uint64_t write_count_problems = 0;  // good writes whose byte count and quantity disagree
  std::uint64_t forbidden_broadcasts = 0;  // good requests to address 0 that may not be broadcast
  std::uint64_t exceptions = 0;
  std::uint64_t gateway_timeouts = 0;  // exceptions 0x0B (EventCounts::gateway_timeouts)
  GapTally gaps;
  LineErrorTally line_errors;  // a bus read from its line's samples (EventCounts::line_errors)

  BusCounters& operator+=(const BusCounters& o);
};

// BusSharing: what the report says of how a bus is shared, for an output that publishes it
// as it goes (MQTT health) without building the whole report. The same rules as BusReport's.
struct BusSharing {
  std::size_t masters = 0;  // 1 for requests of no cycle told apart, 0 before any request
  std::uint64_t collisions = 0;
  std::uint64_t lost_in_collision = 0;
  std::uint64_t echoes = 0;
};

// BusReport: the findings of one bus. Counters cover the whole input; examples are the
// first few of each kind.
struct BusReport : BusCounters {
  static constexpr std::size_t kMaxExamples = 5;

  BusCounters& counters() { return *this; }
  const BusCounters& counters() const { return *this; }

  std::vector<ExceptionTally> exception_codes;  // sorted by dialect and code
  std::vector<FrameExample> bad_check_examples;
  std::vector<TimeoutExample> timeout_examples;
  std::vector<FrameExample> unsolicited_examples;
  bool has_timestamps = true;
  double first_time = 0;  // first and last byte seen, when has_timestamps and bytes arrived
  double last_time = 0;
  TimingReport timing;
  // Sorted by address: the stations a frame with a good check named (station_rule.h).
  std::vector<StationSummary> stations;
  UnknownStation unknown_station;
};

}  // namespace pvtap
