#include "record_dissector.h"

#include <epan/packet.h>

#include "conversation_state.h"
#include "pvtap/segment_cut.h"
#include "stream_dissection.h"

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

// A record holds the bytes of one bus; its first frame tells which framing it uses.
InverterProtocol& protocol_of_record(tvbuff_t* tvb, packet_info* pinfo, RoleHint hint) {
  const guint n = tvb_captured_length(tvb);
  const auto* bytes = static_cast<const guint8*>(tvb_memdup(pinfo->pool, tvb, 0, n));
  const CutOptions options{hint, DialectSet::all(), false};
  for (guint offset = 0; offset < n;) {
    const SegmentCut cut = cut_segment({bytes + offset, n - offset}, options);
    if (cut.kind == SegmentCut::Kind::Frame) return protocol_of(cut.dialect);
    if (cut.length == 0) break;
    offset += static_cast<guint>(cut.length);
  }
  return rtu_protocol();
}

// Dissects a record with one protocol; `data` points to the direction the record carries.
int dissect_record_as(InverterProtocol& p, tvbuff_t* tvb, packet_info* pinfo, proto_tree* tree,
                      void* data) {
  const RoleHint hint = data != nullptr ? *static_cast<const RoleHint*>(data) : RoleHint::Unknown;
  ConversationState& state = conversation_state(pinfo, p);
  const StreamContext ctx{&p, state.matcher, hint, false};
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
  g_proto_records = proto_register_protocol("pvtap bus records", "pvtap", "pvtap");
  register_dissector("pvtap", dissect_record, g_proto_records);
  g_rtu_records = create_dissector_handle(rtu_record, rtu_protocol().proto);
  g_ascii_records = create_dissector_handle(ascii_record, ascii_protocol().proto);
}

}  // namespace pvtap::dissector
