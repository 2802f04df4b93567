// BusTrack: one conversation's bus as the core decides it, with a record of every frame.
#pragma once

#include <epan/packet.h>

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "plan/frame_record.h"
#include "protocol/inverter_protocol.h"
#include "pvtap/session/segmented_bus.h"
#include "pvtap/session/timestamping.h"
#include "stream/held_bytes.h"
#include "stream/station_names.h"
#include "stream/timeout_queue.h"
#include "stream/waiting_records.h"

namespace pvtap::dissector {

// Fed on the first pass only, in capture order; the pieces and records it keeps answer every
// later pass. The session is the one pvtap audit runs for a gateway, so both programs give
// the same frames, verdicts, request links and latencies for the same bytes.
class BusTrack final : public BusSessionSink {
 public:
  // `timestamping`: how the bytes come (a gateway's segments, serial records), which decides what
  // their timestamps prove, as for pvtap audit.
  BusTrack(const ProtocolSettings& settings, Timestamping timestamping);

  SegmentedBus& bus() { return bus_; }
  // Serial records: the bytes not decided yet.
  HeldBytes& held() { return held_; }
  // Serial records: the records whose last byte is not decided yet.
  WaitingRecords& waiting() { return waiting_; }
  // The record of a frame of the session; null for an id it never reported.
  FrameRecord* record(std::uint64_t frame_id) const {
    return frame_id < records_.size() ? records_[frame_id] : nullptr;
  }
  // The requests whose timeout the session reported, for the packet that announces them.
  TimeoutQueue& timeouts() { return timeouts_; }
  // The collisions the session named since the last packet took them; taken by the packet
  // that announces them.
  std::vector<SessionCollision>& collisions() { return collisions_; }
  // Stream position of a TCP sequence number of `d`; the first one seen is position 0.
  std::uint64_t stream_offset(Direction d, guint32 seq);
  // Stream position of the next datagram of `d`, which is `length` bytes long.
  std::uint64_t next_datagram(Direction d, std::size_t length);

 private:
  void on_frame(const SessionFrame& f) override;
  void on_timeout(const SessionTimeout& t) override;
  void on_collision(const SessionCollision& c) override { collisions_.push_back(c); }
  void link(FrameRecord& r, const SessionFrame& f) const;
  void note_findings(FrameRecord& r, const SessionFrame& f);

  SegmentedBus bus_;
  std::vector<FrameRecord*> records_;  // by frame id
  TimeoutQueue timeouts_;
  std::vector<SessionCollision> collisions_;
  std::array<guint32, 3> first_seq_{};
  std::array<bool, 3> seq_known_{};
  std::array<std::uint64_t, 3> datagram_end_{};
  HeldBytes held_;
  WaitingRecords waiting_;
  StationNames names_;
};

// What the session found of a frame, into its record (links aside).
void fill_frame_record(FrameRecord& r, const SessionFrame& f);
// The records a frame's links point to, from the records of its session by frame id.
void link_frame_record(FrameRecord& r, const SessionFrame& f, std::span<FrameRecord* const> by_id);
// A session as pvtap audit runs one for `timestamping`, with the plugin's preferences.
BusSessionOptions bus_session_options(const ProtocolSettings& settings, Timestamping timestamping);
// A new record in file scope, which frees memory without running destructors.
FrameRecord* new_frame_record();

// A track that lives until the capture file is closed.
BusTrack* new_bus_track(const ProtocolSettings& settings,
                        Timestamping timestamping = Timestamping::GatewaySegments);

// Frees every track; registered as a cleanup routine.
void release_bus_tracks();

}  // namespace pvtap::dissector
