#include "registration/transport_entry.h"

#include <epan/conversation.h>

#include <algorithm>
#include <optional>
#include <string>

#include <epan/dissectors/packet-tcp.h>

#include "carriers/modbus_tcp_guard.h"
#include "pvtap/framing/framing_probe.h"
#include "stream/conversation_state.h"
#include "stream/stream_dissection.h"
#include "wireshark_api/heuristic_verdict.h"

namespace pvtap::dissector {
namespace {

using ProtocolOf = InverterProtocol& (*)();

// `tcp`: TCP's struct tcpinfo for TCP payloads, null for datagrams.
int dissect_bound(InverterProtocol& p, tvbuff_t* tvb, packet_info* pinfo, proto_tree* tree,
                  const tcpinfo* tcp) {
  ConversationState& state = conversation_state(pinfo, p);
  set_slave_side_by_port(state, pinfo);
  // Bytes cut off by the snapshot length cannot be completed by later segments.
  const bool whole = tvb_reported_length(tvb) == tvb_captured_length(tvb);
  const StreamContext ctx{&p, state.bus, direction_of(role_hint(state, pinfo)), tcp,
                          tcp != nullptr && p.settings.desegment && pinfo->can_desegment && whole};
  return dissect_stream(tvb, pinfo, tree, ctx);
}

// The role of a frame with a good check at the very start of the payload, if there is one:
// the heuristic claims nothing less, so that other traffic is left alone.
// Over TCP, Modbus/TCP is left to Wireshark's mbtcp, however its first bytes read.
std::optional<Role> leading_frame_role(tvbuff_t* tvb, packet_info* pinfo, DialectSet dialects,
                                       bool tcp) {
  const guint available = tvb_captured_length(tvb);
  if (available < 4) return std::nullopt;
  const guint n = std::min<guint>(available, kMaxFrameLength);
  const auto* bytes = static_cast<const guint8*>(tvb_memdup(pinfo->pool, tvb, 0, n));
  if (tcp && looks_like_modbus_tcp({bytes, n}, available, pinfo->srcport, pinfo->destport)) {
    return std::nullopt;
  }
  const ProbeResult probe = probe_frame({bytes, n}, RoleHint::Unknown, dialects);
  if (probe.status != ProbeResult::Status::Complete || !probe.check.ok) return std::nullopt;
  return probe.role;
}

HeuristicVerdict try_heuristic(InverterProtocol& p, tvbuff_t* tvb, packet_info* pinfo,
                               proto_tree* tree, const tcpinfo* tcp) {
  const std::optional<Role> role = leading_frame_role(tvb, pinfo, p.dialects, tcp != nullptr);
  if (!role) return kDeclined;
  conversation_t* conversation = find_or_create_conversation(pinfo);
  conversation_set_dissector(conversation, tcp != nullptr ? p.stream_handle : p.datagram_handle);
  ConversationState& state = conversation_state(pinfo, p);
  if (!state.slave_known) set_slave_side(state, pinfo, *role == Role::Response);
  dissect_bound(p, tvb, pinfo, tree, tcp);
  return kClaimed;
}

// TCP hands its subdissectors the segment's struct tcpinfo as their data.
const tcpinfo* tcp_info(void* data) {
  return static_cast<const tcpinfo*>(data);
}

template <ProtocolOf P>
int tcp_entry(tvbuff_t* tvb, packet_info* pinfo, proto_tree* tree, void* data) {
  return dissect_bound(P(), tvb, pinfo, tree, tcp_info(data));
}

template <ProtocolOf P>
int datagram_entry(tvbuff_t* tvb, packet_info* pinfo, proto_tree* tree, void*) {
  return dissect_bound(P(), tvb, pinfo, tree, nullptr);
}

template <ProtocolOf P>
HeuristicVerdict tcp_heuristic(tvbuff_t* tvb, packet_info* pinfo, proto_tree* tree, void* data) {
  if (data == nullptr) return kDeclined;
  return try_heuristic(P(), tvb, pinfo, tree, tcp_info(data));
}

template <ProtocolOf P>
HeuristicVerdict udp_heuristic(tvbuff_t* tvb, packet_info* pinfo, proto_tree* tree, void*) {
  return try_heuristic(P(), tvb, pinfo, tree, nullptr);
}

// Wireshark keeps the names it is given, so they are copied to storage never freed.
const char* persistent(const std::string& text) {
  return g_strdup(text.c_str());
}

template <ProtocolOf P>
void create_handles() {
  InverterProtocol& p = P();
  p.stream_handle =
      register_dissector(persistent(std::string(p.filter_name) + "_tcp"), tcp_entry<P>, p.proto);
  p.datagram_handle = register_dissector(p.filter_name, datagram_entry<P>, p.proto);
}

template <ProtocolOf P>
void attach_handles() {
  InverterProtocol& p = P();
  const std::string name(p.filter_name);
  dissector_add_uint_range_with_preference("tcp.port", "", p.stream_handle);
  dissector_add_uint_range_with_preference("udp.port", "", p.datagram_handle);
  heur_dissector_add("tcp", tcp_heuristic<P>, persistent(std::string(p.name) + " over TCP"),
                     persistent(name + "_tcp"), p.proto, HEURISTIC_ENABLE);
  heur_dissector_add("udp", udp_heuristic<P>, persistent(std::string(p.name) + " over UDP"),
                     persistent(name + "_udp"), p.proto, HEURISTIC_ENABLE);
  dissector_add_for_decode_as("rtacser.data", p.datagram_handle);
}

}  // namespace

void register_transport_dissectors(InverterProtocol& p) {
  if (&p == &rtu_protocol()) {
    create_handles<rtu_protocol>();
  } else {
    create_handles<ascii_protocol>();
  }
}

void register_transport_handoffs(InverterProtocol& p) {
  if (&p == &rtu_protocol()) {
    attach_handles<rtu_protocol>();
  } else {
    attach_handles<ascii_protocol>();
  }
}

}  // namespace pvtap::dissector
