// What the transaction matcher decides, as values.
#pragma once

#include <cstdint>
#include <optional>
#include <span>

#include "pvtap/codec/dialect.h"

namespace pvtap {

// ReplyKind: whether a reply carries data or says the request failed.
enum class ReplyKind : std::uint8_t {
  Normal = 0,
  HybridError = 1,   // Hybrid function 0xFF, answers any pending Hybrid request
  GslException = 2,  // GSL fc|0x80 with an exception code
};

// Transaction: a request and the reply that answered it.
struct Transaction {
  std::uint64_t request_id = 0;
  std::uint64_t response_id = 0;
  double latency = 0;  // reply start_time - request end_time, seconds (may be < 0 on coarse clocks)
  Dialect dialect = kDefaultDialect;
  std::uint8_t station = 0;   // the answering station (its real address for a broadcast)
  std::uint8_t function = 0;  // the request's function code
  std::uint8_t reply_function = 0;
  ReplyKind reply_kind = ReplyKind::Normal;
  bool broadcast = false;  // the request went to the Hybrid broadcast address 0xFF
  bool request_check_ok = true;
  bool reply_check_ok = true;  // false: the slave answered but the line corrupted the reply
};

// TimeoutReason: why a request is given up without a reply.
enum class TimeoutReason : std::uint8_t {
  NoReply = 0,           // nothing answered within the configured timeout
  NextRequestFirst = 1,  // the master sent the next request to that station first
  CaptureEnded = 2,      // the capture ended while the request waited
  // The carrier answered in the reply's place that no reply came from the bus (a logger
  // stick's code 05; Timeout::carrier_code).
  CarrierNoReply = 3,
};

// Timeout: a request that got no reply.
struct Timeout {
  std::uint64_t request_id = 0;
  Dialect dialect = kDefaultDialect;
  std::uint8_t station = 0;  // 0xFF for a Hybrid broadcast that nobody answered
  std::uint8_t function = 0;
  TimeoutReason reason = TimeoutReason::NoReply;
  double waited = 0;  // seconds from the request's end to the moment it was given up
  std::optional<std::uint64_t> next_request_id;  // set for NextRequestFirst
  // False: the request itself had a bad check, so the slave was right to stay silent.
  bool request_check_ok = true;
  std::uint8_t carrier_code = 0;  // CarrierNoReply: the code the carrier answered
};

// UnsolicitedReply: a reply that no pending request of its station (or broadcast) expects.
struct UnsolicitedReply {
  std::uint64_t response_id = 0;
  Dialect dialect = kDefaultDialect;
  std::uint8_t station = 0;
  std::uint8_t function = 0;
  bool check_ok = true;
  // When the reply fits a request that already timed out, that request and how long after
  // its end the reply began: the master's timeout is probably too short.
  std::optional<std::uint64_t> late_for_request_id;
  double since_request = 0;
};

// DuplicateReply: a station answered the same request again with no new request in between.
// When both replies had good checks and the length the request asked for, and their bytes
// differ, two devices answer to one address (an address conflict): a device repeating itself
// sends the same bytes again, and a reply of another length answers another master's request.
struct DuplicateReply {
  std::uint64_t response_id = 0;
  std::uint64_t original_request_id = 0;
  Dialect dialect = kDefaultDialect;
  std::uint8_t station = 0;
  std::uint8_t function = 0;
  bool check_ok = true;
  bool other_content = false;
  double since_request = 0;  // from the request's end to this reply's start, seconds
};

// EchoedRequest: a request seen a second time, byte for byte, as soon as it ended: the tap's
// own adapter echoing what its master sent. It is one request on the bus, not two.
struct EchoedRequest {
  std::uint64_t echo_id = 0;
  std::uint64_t request_id = 0;  // the request it repeats
};

// CountUnit: what ByteCountMismatch counts.
enum class CountUnit : std::uint8_t { Bytes = 0, Words = 1 };

// ByteCountMismatch: a reply whose length field disagrees with what its request asked for.
struct ByteCountMismatch {
  std::uint64_t request_id = 0;
  std::uint64_t response_id = 0;
  Dialect dialect = kDefaultDialect;
  std::uint8_t station = 0;
  std::uint8_t function = 0;
  unsigned expected = 0;
  unsigned found = 0;
  CountUnit unit = CountUnit::Bytes;  // ASCII replies are judged in words
};

// RoleCorrection: a frame whose reported role was wrong (the GSL 0x06 echo read as a request).
struct RoleCorrection {
  std::uint64_t frame_id = 0;
  std::uint64_t request_id = 0;  // the request this frame echoes
  Role reported = Role::Request;
  Role corrected = Role::Response;
};

// FrameMatch: what the matcher decided for one frame, in the order it was decided: the
// timeouts (those the frame's start made due, then the request a new request to the same
// station gave up), the role correction, the transaction, duplicate or unsolicited reply
// (at most one of them), the length mismatch. An echo decides nothing else. `timeouts` points into
// the matcher and is valid until its next call.
struct FrameMatch {
  Role role = Role::Request;  // as corrected (a GSL 0x06 echo is a response)
  std::span<const Timeout> timeouts;
  std::optional<RoleCorrection> role_correction;
  std::optional<Transaction> transaction;
  std::optional<DuplicateReply> duplicate;
  std::optional<UnsolicitedReply> unsolicited;
  std::optional<ByteCountMismatch> count_mismatch;
  std::optional<EchoedRequest> echo;
};

}  // namespace pvtap
