// ConversationState: per conversation and protocol, which side is the slave, and the bus.
#pragma once

#include <epan/address.h>
#include <epan/packet.h>

#include "protocol/inverter_protocol.h"
#include "stream/bus_track.h"

namespace pvtap::dissector {

// Lives in wmem file scope. The slave side is the gateway's: it sends the responses.
struct ConversationState {
  address slave_address = ADDRESS_INIT_NONE;
  guint32 slave_port = 0;
  bool slave_known = false;
  BusTrack* bus = nullptr;
};

// The state of the packet's conversation for a protocol, made on first use with a bus for
// `timestamping`.
ConversationState& conversation_state(packet_info* pinfo, InverterProtocol& protocol,
                                      Timestamping timestamping = Timestamping::GatewaySegments);

// Records which side is the slave: the sender of this packet, or its receiver.
void set_slave_side(ConversationState& state, packet_info* pinfo, bool sender_is_slave);

// Binds the side whose port matched a port preference (or Decode As) as the slave side.
void set_slave_side_by_port(ConversationState& state, packet_info* pinfo);

// Request when the packet goes to the slave, Response when it comes from it.
RoleHint role_hint(const ConversationState& state, const packet_info* pinfo);

}  // namespace pvtap::dissector
