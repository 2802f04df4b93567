// Timeline: what the HTML report draws over time, gathered from the bus sessions' events by
// TimelineCollector: per-station lanes of requests, replies and findings, bus load, latency,
// register values and the silences in polling. Counters and statistics are not here: they
// are AuditReport's.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "html/time_buckets.h"
#include "pvtap/codec/dialect.h"
#include "pvtap/registers/register_map.h"
#include "pvtap/session/bus_report.h"

namespace pvtap::analyzer {

// MarkKind: a finding drawn as one mark on its station's lane.
enum class MarkKind : std::uint8_t {
  Damaged,            // a frame with a bad check
  Timeout,            // a good request the slave did not answer
  UnansweredDamaged,  // a damaged request its slave rightly ignored
  Exception,          // a GSL exception or a Hybrid error reply
  Unsolicited,
  Duplicate,
  Noise,      // on the bus lane
  Gap,        // capture data lost; on the bus lane
  Collision,  // two transmissions at once; on the bus lane
};
inline constexpr std::size_t kMarkKinds = 9;

// Mark: one finding with what its tooltip names.
struct Mark {
  double time = 0;
  std::uint32_t lane = 0;
  MarkKind kind = MarkKind::Damaged;
  Dialect dialect = kDefaultDialect;
  bool has_function = false;
  std::uint8_t function = 0;
  bool is_request = false;
  std::optional<std::uint16_t> start;  // the block: wire start address and count
  std::optional<std::uint16_t> count;
  std::uint64_t detail = 0;  // bytes of noise or of a gap; the exception code
};

// Lane: one station of one bus, or the bus itself (station empty) for noise and gaps.
struct Lane {
  std::string bus;
  std::optional<std::uint8_t> station;
  BucketSeries requests;  // count per bucket
  BucketSeries replies;
  BucketSeries latency;  // seconds: min, max, mean per bucket
  // Reply latency histogram: bin i counts latencies in [10^(i/10) ms, 10^((i+1)/10) ms);
  // bin 0 also takes anything faster than 1 ms, the last anything slower than 10 s.
  static constexpr std::size_t kLatencyBins = 40;
  std::array<std::uint64_t, kLatencyBins> latency_bins{};
};

// BusLoad: bytes per bucket on one bus, by direction (requests to the slaves, replies from
// them; noise in the direction it came from, or apart when a tap cannot tell).
struct BusLoad {
  std::string bus;
  BucketSeries to_slave;
  BucketSeries from_slave;
  BucketSeries unknown;
};

// ValueSeries: one register of one station, numeric readings only.
struct ValueSeries {
  std::uint32_t lane = 0;
  Dialect dialect = kDefaultDialect;
  const RegisterDef* def = nullptr;  // points into the register map; null: an unmapped word
  std::uint16_t instance = 0;
  RegisterTable table = RegisterTable::Registers;  // of an unmapped word
  std::string key;                                 // the map's key, or "reg_0x0003"
  std::string address;                             // as the reference writes it
  BucketSeries points;
  double min = 0, max = 0;  // over the whole run
  bool changed() const { return min != max; }
};

// PollSilence: a stretch in which the logger asked nothing on a bus.
struct PollSilence {
  std::string bus;
  double from = 0;
  double to = 0;
};

struct Timeline {
  static constexpr std::size_t kMaxMarksPerKind = 20000;
  static constexpr std::size_t kMaxSilences = 1000;
  // Silences shorter than this are not kept (the report keeps those longer than twice the
  // bus's poll period).
  static constexpr double kMinSilence = 2.0;

  bool has_timestamps = true;
  double start = 0;         // of bucket 0
  double bucket_width = 0;  // seconds
  std::vector<Lane> lanes;
  std::vector<BusLoad> loads;
  std::vector<ValueSeries> values;
  std::vector<Mark> marks;                                // in time order per kind
  std::array<std::uint64_t, kMarkKinds> marks_dropped{};  // beyond kMaxMarksPerKind
  std::vector<PollSilence> silences;
};

}  // namespace pvtap::analyzer
