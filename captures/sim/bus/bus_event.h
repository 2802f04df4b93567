// BusEvent: one run of bytes on the simulated RS485 bus (a frame or noise) with its timing,
// and what the ground truth says about it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "pvtap/codec/dialect.h"

namespace pvtap::sim {

using Micros = std::int64_t;  // simulated time, microseconds since the Unix epoch

// DeviceLabel: what the ground truth says a plain Modbus device is ("meter", "io_module") and
// the names its device identification gives (empty when it answers none).
struct DeviceLabel {
  std::string kind;
  std::string vendor, product, revision;
  std::string name;  // the text of its report server ID reply, when it answers one
};

// RegisterTruth: the value one register held when an inverter answered.
struct RegisterTruth {
  std::string address;  // as the reference writes it ("0x1006", "1056")
  std::string key;
  std::uint32_t raw = 0;
  double value = 0.0;  // raw x scale (signed when the map says so)
  bool numeric = false;
  std::string text;  // text registers: the characters (printable ASCII; raw is the first word)
};

struct BusEvent {
  enum class Kind { Frame, Noise } kind = Kind::Frame;
  Micros start = 0;  // first byte on the wire
  Micros end = 0;    // last byte on the wire
  std::vector<std::uint8_t> bytes;
  Dialect dialect = kDefaultDialect;
  Role role = Role::Request;  // noise: the slave side, where a gateway forwards it from
  std::uint8_t station = 0;
  std::uint8_t function = 0;
  bool check_ok = true;
  std::string fault;   // empty when the event is clean (noise: "noise", or the fault that
                       // damaged an ASCII frame beyond delimiting)
  Micros latency = 0;  // replies: from the end of the request to the first byte
  std::vector<RegisterTruth> values;
  // A shared bus (--masters 2): the master whose exchange (its request and what answered it)
  // the event belongs to, and that exchange's number, counted from 1 over the run.
  std::uint8_t master = 1;
  std::uint32_t exchange = 0;
};

// TimeoutTruth: a request that the master gave up on (station and function as its bytes say).
struct TimeoutTruth {
  Micros request_start = 0;
  Micros request_end = 0;
  std::uint8_t station = 0;
  std::uint8_t function = 0;
  std::string reason;  // empty: no reply came; else why a carrier says none came
};

// FaultTruth: one fault the simulator injected, at the end of the request it spoiled.
struct FaultTruth {
  Micros time = 0;
  std::uint8_t station = 0;
  std::string kind;
};

// LayoutTruth: the type of one value a plain Modbus device holds, the truth an analyzer's
// inference of unmapped registers is scored against.
struct LayoutTruth {
  std::uint8_t function = 0;  // 0x03 holding, 0x04 input
  std::uint16_t address = 0;  // first register
  std::uint8_t words = 1;
  // u16 s16 u32 s32 float32 text bits unused (0xFFFF or 0x8000 fill)
  std::string type;
  bool low_first = false;  // 2-word values: the low word comes first on the wire
  bool counter = false;    // only grows (and wraps)
  std::string key;
};

// DeviceTruth: a plain Modbus device on the bus, what it is and what its registers hold.
struct DeviceTruth {
  std::uint8_t station = 0;
  DeviceLabel label;
  std::vector<LayoutTruth> layout;  // empty for devices that publish none
};

// PollTruth: one block of a master's poll plan.
struct PollTruth {
  std::uint8_t station = 0;
  std::uint8_t function = 0;
  std::uint16_t start = 0;
  std::uint16_t count = 0;
};

// MasterTruth: one master on a shared bus, its plan and its cycle.
struct MasterTruth {
  std::uint8_t master = 1;
  double period_s = 0;
  Micros turnaround_min = 0, turnaround_max = 0;  // from a reply's end to its next request
  std::vector<PollTruth> plan;
};

// DestroyedExchange: an exchange a collision destroyed: its request itself, or (the request
// heard whole) the reply to it.
struct DestroyedExchange {
  std::uint8_t master = 1;
  std::uint8_t station = 0;
  std::uint8_t function = 0;
  Micros request_start = 0;
  bool request_lost = false;
};

// CollisionTruth: two transmissions that overlapped on the line, and what they destroyed.
struct CollisionTruth {
  Micros start = 0;  // the first of the two began
  Micros end = 0;    // the last of the two ended
  std::vector<DestroyedExchange> destroyed;
};

// ConflictTruth: a second device answering to an address that already has one.
struct ConflictTruth {
  std::uint8_t station = 0;
  std::uint64_t second_replies = 0;  // replies of the second device that reached the line whole
};

// BusTimeline: everything the simulated bus carried, in time order.
struct BusTimeline {
  std::vector<BusEvent> events;
  std::vector<TimeoutTruth> timeouts;  // good requests that got no reply a reader can see
  // Requests with a bad check, rightly ignored by their slave: not timeouts.
  std::vector<TimeoutTruth> unanswered_damaged_requests;
  std::vector<FaultTruth> faults;
  // Requests still waiting when the capture ends: no capture can show their timeout.
  std::vector<TimeoutTruth> unanswered_at_end;
  std::vector<DeviceTruth> devices;  // the plain Modbus devices, in poll order
  // A shared bus: its masters (listed only with --masters 2), the collisions, the address
  // conflict and the requests an echoing adapter gave twice.
  std::vector<MasterTruth> masters;
  std::vector<CollisionTruth> collisions;
  std::vector<ConflictTruth> conflicts;
  std::uint64_t echoes = 0;
};

}  // namespace pvtap::sim
