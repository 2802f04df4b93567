// CallView: what one call of the plugin for a bus shows, decided on the first pass.
#pragma once

#include <epan/packet.h>

#include <cstdint>

#include "plan/frame_record.h"
#include "stream/bus_track.h"
#include "stream/timeout_queue.h"

namespace pvtap::dissector {

// Lives in wmem file scope; later passes show what the first pass noted.
struct CallView {
  std::uint64_t from = 0;            // stream position of the first byte of the call's pieces
  std::uint64_t decided_to = 0;      // the bytes after it wait for more
  std::uint64_t shown_to = 0;        // the pieces in [from, shown_to) are this call's to show
  bool extends_pdu = false;          // a call later passes do not make (it shows nothing)
  FrameRecord** timeouts = nullptr;  // the timeouts this call announces
  std::uint32_t timeout_count = 0;
  SessionCollision* collisions = nullptr;  // the collisions this call announces
  std::uint32_t collision_count = 0;
  std::uint64_t record_from = 0;          // serial records: stream position of the record's bytes
  const std::uint8_t* earlier = nullptr;  // serial records: the bytes in [from, record_from)
  // Serial records whose last byte waits for a later record: the protocol the waiting bytes
  // resemble (null when none waits), and, once a later record of the first pass decided that
  // byte, that record and the frame holding the byte (null for noise).
  const InverterProtocol* waits_under = nullptr;
  std::uint32_t completed_in = 0;
  const FrameRecord* completed_by = nullptr;
};

// The view the first pass noted for call `number` of `proto` in the packet; null if none.
CallView* noted_view(packet_info* pinfo, int proto, guint32 number);

// A new view for call `number`, kept for later passes.
CallView& note_view(packet_info* pinfo, int proto, guint32 number);

// First pass: the requests of `queue` whose own packet is known, announced by this packet (their
// announced_in set), as an array in file scope of `count` entries (null when none).
FrameRecord** announce_timeouts(packet_info* pinfo, TimeoutQueue& queue, std::uint32_t& count);

// First pass, once the call's pieces are shown: the timeouts and collisions it announces (none
// when a later pass will not make the call).
void note_timeouts(CallView& view, packet_info* pinfo, BusTrack& bus);

// Shows the timeouts and collisions the view announces.
void show_timeouts(const CallView& view, tvbuff_t* tvb, packet_info* pinfo, proto_tree* tree);

}  // namespace pvtap::dissector
