#include "carriers/solarman_v5_entry.h"

#include <epan/conversation.h>
#include <epan/dissectors/packet-tcp.h>

#include <algorithm>
#include <span>

#include "carriers/modbus_tcp_guard.h"
#include "carriers/solarman_v5_dissection.h"
#include "carriers/solarman_v5_protocol.h"
#include "pvtap/carriers/solarman_v5_frame.h"
#include "pvtap/carriers/solarman_v5_structure.h"
#include "stream/conversation_state.h"

namespace pvtap::dissector {
namespace {

namespace v5 = solarman_v5;

// V5Conversation: the stick's side and the RTU bus (invrtu's state of the conversation, on a
// bus timed as pvtap audit times a stick's), and the V5 track.
struct V5Conversation {
  ConversationState* side = nullptr;
  SolarmanV5Track* track = nullptr;
};

V5Conversation v5_conversation(packet_info* pinfo) {
  const int proto = v5_protocol().proto;
  ConversationState& side =
      conversation_state(pinfo, rtu_protocol(), Timestamping::LoggerStickFrames);
  conversation_t* conversation = find_or_create_conversation(pinfo);
  auto* track = static_cast<SolarmanV5Track*>(conversation_get_proto_data(conversation, proto));
  if (track == nullptr) {
    track = new_v5_track(*side.bus, rtu_protocol().settings);
    conversation_add_proto_data(conversation, proto, track);
  }
  return V5Conversation{&side, track};
}

// The stick sends responses and its own frames; the client sends requests and answers them.
bool sent_by_stick(std::uint16_t control) {
  const v5::FrameKind kind = v5::kind_of(control);
  return kind == v5::FrameKind::Response || kind == v5::FrameKind::StickFrame;
}

// The start of a frame cut short: start byte, a known control code and a length in range.
bool opens_like_v5(std::span<const std::uint8_t> b) {
  if (b.size() < 5 || b[0] != v5::kStart) return false;
  const auto length = static_cast<std::size_t>(b[1] | (b[2] << 8));
  const auto control = static_cast<std::uint16_t>(b[3] | (b[4] << 8));
  return length <= v5::kMaxPayload && v5::known_control(control);
}

}  // namespace

int dissect_v5_tcp(tvbuff_t* tvb, packet_info* pinfo, proto_tree* tree, void* data) {
  const auto* tcp = static_cast<const tcpinfo*>(data);
  if (tcp == nullptr) return 0;
  const V5Conversation c = v5_conversation(pinfo);
  set_slave_side_by_port(*c.side, pinfo);
  // Bytes cut off by the snapshot length cannot be completed by later segments.
  const bool whole = tvb_reported_length(tvb) == tvb_captured_length(tvb);
  const bool desegment = rtu_protocol().settings.desegment && pinfo->can_desegment && whole;
  const V5Context ctx{c.track, direction_of(role_hint(*c.side, pinfo)), tcp, desegment};
  return dissect_v5_stream(tvb, pinfo, tree, ctx);
}

// Claims a TCP payload that opens with a whole V5 frame whose end byte, checksum and control
// code hold; Modbus/TCP is left to Wireshark's mbtcp, however its first bytes read.
HeuristicVerdict v5_tcp_heuristic(tvbuff_t* tvb, packet_info* pinfo, proto_tree* tree, void* data) {
  if (data == nullptr) return kDeclined;
  const guint available = tvb_captured_length(tvb);
  if (available < 5) return kDeclined;
  const guint n = std::min<guint>(available, v5::kOverhead + v5::kMaxPayload);
  const auto* bytes = static_cast<const guint8*>(tvb_memdup(pinfo->pool, tvb, 0, n));
  if (looks_like_modbus_tcp({bytes, n}, available, pinfo->srcport, pinfo->destport)) {
    return kDeclined;
  }
  const v5::Recognition recognition = v5::recognize({bytes, n});
  if (recognition == v5::Recognition::NeedMore && opens_like_v5({bytes, n}) &&
      pinfo->can_desegment) {
    // The first frame is cut by its segment: TCP offers the heuristics the bytes again with
    // the next segment, and nothing is bound until the whole frame holds.
    pinfo->desegment_offset = 0;
    pinfo->desegment_len = DESEGMENT_ONE_MORE_SEGMENT;
    return kClaimed;
  }
  if (recognition != v5::Recognition::Yes) return kDeclined;
  conversation_set_dissector(find_or_create_conversation(pinfo), v5_protocol().handle);
  const V5Conversation c = v5_conversation(pinfo);
  if (!c.side->slave_known) {
    set_slave_side(*c.side, pinfo, sent_by_stick(v5::read_header({bytes, n}).control));
  }
  dissect_v5_tcp(tvb, pinfo, tree, data);
  return kClaimed;
}

}  // namespace pvtap::dissector
