// FrameRecord: what the first pass learned about one frame, kept for every later pass.
#pragma once

#include <epan/wmem_scopes.h>
#include <wsutil/nstime.h>

#include <type_traits>

#include "pvtap/codec/dialect.h"
#include "pvtap/matching/match_events.h"
#include "pvtap/session/bus_session.h"

namespace pvtap::dissector {

// Lives in wmem file scope, which frees memory without running destructors.
struct FrameRecord {
  guint32 packet = 0;  // the packet that shows the frame (0 until it is shown)
  nstime_t time{};     // that packet's capture time
  Dialect dialect = Dialect::Gsl;
  Role role = Role::Request;  // after the matcher's correction of GSL write echoes
  guint8 station = 0;
  guint8 function = 0;
  bool matched = false;  // the session paired it (its header could be read)
  bool check_ok = true;
  bool role_corrected = false;
  bool timed_out = false;
  bool unsolicited = false;
  bool duplicate = false;
  bool count_mismatch = false;
  bool has_latency = false;
  bool values_trusted = false;  // a good check: its values may be decoded
  TimeoutReason timeout_reason = TimeoutReason::NoReply;
  UnansweredKind unanswered = UnansweredKind::Timeout;
  double latency = 0;  // replies: seconds from the request's end to the reply's start
  CountUnit count_unit = CountUnit::Bytes;
  guint16 count_expected = 0;
  guint16 count_found = 0;
  FrameRecord* request = nullptr;       // replies: the request answered (or answered before)
  FrameRecord* response = nullptr;      // requests: the first reply
  FrameRecord* late_for = nullptr;      // unsolicited replies: a request that timed out
  FrameRecord* next_request = nullptr;  // requests given up for the next one to the station
  FrameRecord* placed_by = nullptr;     // the request whose start places a reply's words
  const guint8* bytes = nullptr;        // requests: their bytes, to decode their replies
  guint16 length = 0;
};

static_assert(std::is_trivially_destructible_v<FrameRecord>);

// A new record in file scope.
inline FrameRecord* new_frame_record() {
  return new (wmem_alloc(wmem_file_scope(), sizeof(FrameRecord))) FrameRecord{};
}

}  // namespace pvtap::dissector
