// MbapTrack: one Modbus/TCP conversation read as pvtap audit reads it, a record per ADU.
#pragma once

#include <cstdint>
#include <map>
#include <span>
#include <utility>
#include <vector>

#include "plan/frame_record.h"
#include "protocol/inverter_protocol.h"
#include "pvtap/carriers/mbap_flow.h"
#include "stream/station_names.h"
#include "stream/timeout_queue.h"

namespace pvtap::dissector {

// Fed on the first pass only, one whole ADU at a time (TCP reassembled it), in capture order.
// The session and the pairing by transaction id are pvtap audit's (MbapFlow), so both
// programs give the same frames, request links, latencies and exceptions for the same bytes.
// A request is paired when its reply comes: until then its record holds what the request
// says of itself.
class MbapTrack final : public BusSessionSink {
 public:
  explicit MbapTrack(const ProtocolSettings& settings);

  // The record of the ADU whose station byte and PDU are `frame`, fed now.
  FrameRecord* feed(Direction d, std::span<const std::uint8_t> adu, double time);

  // The requests whose timeout the session reported, for the packet that announces them, as
  // invrtu's serial and gateway buses do.
  TimeoutQueue& timeouts() { return timeouts_; }

 private:
  void on_frame(const SessionFrame& f) override;
  void on_timeout(const SessionTimeout& t) override;

  BusSession session_;
  MbapFlow flow_;
  std::map<std::pair<Direction, std::uint64_t>, FrameRecord*> by_offset_;
  std::vector<FrameRecord*> by_id_;
  TimeoutQueue timeouts_;
  StationNames names_;
};

// A track that lives until the capture file is closed (release_bus_tracks frees it).
MbapTrack* new_mbap_track(const ProtocolSettings& settings);
void release_mbap_tracks();

}  // namespace pvtap::dissector
