#include "registration/record_dissector.h"

#include <epan/packet.h>

#include <algorithm>

#include "fields/field_list.h"
#include "pvtap/pcap/exported_pdu_tags.h"
#include "registration/record_layer.h"
#include "stream/conversation_state.h"
#include "stream/stream_dissection.h"

namespace pvtap::dissector {
namespace {

int g_proto_records = -1;
int g_hf_event = -1;
// The longest text of an event record shown; the analyzer writes one short line.
constexpr int kMaxEventText = 256;

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
  const StreamContext ctx{
      .protocol = &p, .bus = state.bus, .direction = direction_of(hint), .names_talkers = true};
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

// A record that marks a moment (the end of the run, capture data lost): its text in the Info
// column and the tree, so that no record of the file shows blank. No C++ object lives here:
// the tvb accessors may longjmp.
int dissect_event(tvbuff_t* tvb, packet_info* pinfo, proto_tree* tree, void*) {
  const int length = static_cast<int>(
      std::min<unsigned>(tvb_captured_length(tvb), static_cast<unsigned>(kMaxEventText)));
  const guint8* text = tvb_get_string_enc(pinfo->pool, tvb, 0, length, ENC_UTF_8);
  col_set_str(pinfo->cinfo, COL_PROTOCOL, "pvtap");
  col_add_str(pinfo->cinfo, COL_INFO, reinterpret_cast<const char*>(text));
  proto_tree_add_item(tree, g_proto_records, tvb, 0, -1, ENC_NA);
  proto_tree_add_item(tree, g_hf_event, tvb, 0, length, ENC_UTF_8);
  return static_cast<int>(tvb_captured_length(tvb));
}

}  // namespace

void register_record_dissector() {
  g_proto_records = proto_register_protocol("pvtap bus records", exported_pdu::kDissectorName,
                                            exported_pdu::kDissectorName);
  register_dissector(exported_pdu::kDissectorName, dissect_record, g_proto_records);
  static FieldList fields;
  fields.add(&g_hf_event, "Event", "pvtap.event", FT_STRING, BASE_NONE, nullptr, 0,
             "What a record of pvtap's own capture marks: the end of the run, capture data lost");
  fields.register_all(g_proto_records);
  register_dissector(exported_pdu::kEventDissectorName, dissect_event, g_proto_records);
  g_rtu_records = create_dissector_handle(rtu_record, rtu_protocol().proto);
  g_ascii_records = create_dissector_handle(ascii_record, ascii_protocol().proto);
}

}  // namespace pvtap::dissector
