#include "registration/record_dissector.h"

#include <epan/packet.h>

#include "pvtap/capture/exported_pdu_tags.h"
#include "registration/record_layer.h"
#include "stream/conversation_state.h"
#include "stream/stream_dissection.h"

namespace pvtap::dissector {
namespace {

int g_proto_records = -1;

// The exported-PDU direction tag, as the analyzer writes it (dissector/README.md).
RoleHint hint_of(const packet_info* pinfo) {
  switch (pinfo->p2p_dir) {
    case P2P_DIR_SENT:
      return RoleHint::Request;  // master to slave
    case P2P_DIR_RECV:
      return RoleHint::Response;  // slave to master
    default:
      return RoleHint::Unknown;
  }
}

// Dissects a record; `data` points to the direction the record carries. All records of a
// capture are one bus (one matcher), whatever layer shows them.
int dissect_record_as(InverterProtocol& p, tvbuff_t* tvb, packet_info* pinfo, proto_tree* tree,
                      void* data) {
  const RoleHint hint = data != nullptr ? *static_cast<const RoleHint*>(data) : RoleHint::Unknown;
  ConversationState& state = conversation_state(pinfo, rtu_protocol());
  const StreamContext ctx{&p, state.bus, direction_of(hint), nullptr, false};
  return dissect_stream(tvb, pinfo, tree, ctx);
}

int rtu_record(tvbuff_t* tvb, packet_info* pinfo, proto_tree* tree, void* data) {
  return dissect_record_as(rtu_protocol(), tvb, pinfo, tree, data);
}

int ascii_record(tvbuff_t* tvb, packet_info* pinfo, proto_tree* tree, void* data) {
  return dissect_record_as(ascii_protocol(), tvb, pinfo, tree, data);
}

dissector_handle_t g_rtu_records = nullptr;
dissector_handle_t g_ascii_records = nullptr;

// Hands the record to the protocol of its framing, so that the protocol shows as its own layer.
int dissect_record(tvbuff_t* tvb, packet_info* pinfo, proto_tree* tree, void*) {
  RoleHint hint = hint_of(pinfo);
  const InverterProtocol& p = protocol_of_record(tvb, pinfo, hint);
  dissector_handle_t handle = &p == &ascii_protocol() ? g_ascii_records : g_rtu_records;
  return call_dissector_with_data(handle, tvb, pinfo, tree, &hint);
}

}  // namespace

void register_record_dissector() {
  g_proto_records = proto_register_protocol("pvtap bus records", exported_pdu::kDissectorName,
                                            exported_pdu::kDissectorName);
  register_dissector(exported_pdu::kDissectorName, dissect_record, g_proto_records);
  g_rtu_records = create_dissector_handle(rtu_record, rtu_protocol().proto);
  g_ascii_records = create_dissector_handle(ascii_record, ascii_protocol().proto);
}

}  // namespace pvtap::dissector
