#include "stream/conversation_state.h"

#include <epan/conversation.h>

namespace pvtap::dissector {

ConversationState& conversation_state(packet_info* pinfo, InverterProtocol& p,
                                      Timestamping timestamping) {
  conversation_t* conversation = find_or_create_conversation(pinfo);
  auto* state = static_cast<ConversationState*>(conversation_get_proto_data(conversation, p.proto));
  if (state == nullptr) {
    state = new (wmem_alloc(wmem_file_scope(), sizeof(ConversationState))) ConversationState{};
    state->bus = new_bus_track(p.settings, timestamping);
    conversation_add_proto_data(conversation, p.proto, state);
  }
  return *state;
}

void set_slave_side(ConversationState& state, packet_info* pinfo, bool sender_is_slave) {
  const address& side = sender_is_slave ? pinfo->src : pinfo->dst;
  copy_address_wmem(wmem_file_scope(), &state.slave_address, &side);
  state.slave_port = sender_is_slave ? pinfo->srcport : pinfo->destport;
  state.slave_known = true;
}

void set_slave_side_by_port(ConversationState& state, packet_info* pinfo) {
  if (state.slave_known || pinfo->match_uint == 0) return;
  if (pinfo->match_uint == pinfo->destport) {
    set_slave_side(state, pinfo, false);
  } else if (pinfo->match_uint == pinfo->srcport) {
    set_slave_side(state, pinfo, true);
  }
}

RoleHint role_hint(const ConversationState& state, const packet_info* pinfo) {
  if (!state.slave_known) return RoleHint::Unknown;
  const bool from_slave =
      addresses_equal(&pinfo->src, &state.slave_address) && pinfo->srcport == state.slave_port;
  return from_slave ? RoleHint::Response : RoleHint::Request;
}

}  // namespace pvtap::dissector
