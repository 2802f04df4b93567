#include "registration/serial_link_types.h"

#include <epan/packet.h>
#include <epan/prefs.h>
#include <wiretap/wtap.h>

#include "fields/field_list.h"
#include "registration/record_layer.h"
#include "stream/conversation_state.h"
#include "stream/record_dissection.h"
#include "wireshark_api/preference_types.h"

namespace pvtap::dissector {
namespace {

SerialRecordFields g_fields;
dissector_handle_t g_serial_handle = nullptr;
// Serial sniffers (SerialPCAP, modbus-sniffer, WiresharkSerialAdapter) write USER0-15; a user
// who maps them to another protocol turns this off.
PreferenceBool g_claim_serial_payloads = true;

// As pvtap audit: records of more than one byte are chunks read from an adapter, whose
// timestamps are batched; one byte per record is a tap that stamps each character. The first
// record decides, since a first pass cannot look ahead.
Timestamping timestamping_of(tvbuff_t* tvb) {
  return tvb_captured_length(tvb) > 1 ? Timestamping::SerialBatches
                                      : Timestamping::SerialCharacters;
}

int dissect_serial(tvbuff_t* tvb, packet_info* pinfo, proto_tree* tree, void*) {
  // All records of a capture are one bus, whatever layer shows them.
  ConversationState& state = conversation_state(pinfo, rtu_protocol(), timestamping_of(tvb));
  return dissect_serial_record(tvb, pinfo, tree, protocol_of_record(tvb, pinfo, RoleHint::Unknown),
                               *state.bus, g_fields);
}

// RTAC serial records carry bus bytes too (the RTAC dissector looks its payload up under 0):
// ours unless Decode As chose a protocol for them.
void claim_rtac_payloads() {
  dissector_table_t table = find_dissector_table("rtacser.data");
  if (table != nullptr && dissector_get_uint_handle(table, 0) == nullptr) {
    dissector_change_uint("rtacser.data", 0, g_serial_handle);
  }
}

// USER0-15 (as the preference says) and RTAC payloads.
void claim_serial_payloads() {
  claim_rtac_payloads();
  const bool on = g_claim_serial_payloads;
  for (int encap = WTAP_ENCAP_USER0; encap <= WTAP_ENCAP_USER15; ++encap) {
    if (on) {
      dissector_change_uint("wtap_encap", static_cast<guint32>(encap), g_serial_handle);
    } else {
      dissector_reset_uint("wtap_encap", static_cast<guint32>(encap));
    }
  }
}

// The fields of a record whose last byte waits for a later record.
void register_waiting_fields() {
  static FieldList fields;
  fields.add(&g_fields.waiting, "Bytes waiting for a later record", "pvtap_serial.waiting",
             FT_UINT32, BASE_DEC, nullptr, 0,
             "Bytes of this record that belong to a frame (or noise run) shown by a later record");
  fields.add(&g_fields.completed_in, "Completed in", "pvtap_serial.completed_in", FT_FRAMENUM,
             BASE_NONE, nullptr, 0,
             "The record that completes the frame holding this record's last byte, and shows it "
             "(known once the capture has been read: not in a single pass)");
  fields.register_all(g_fields.proto);
  static int* subtrees[] = {&g_fields.ett};
  proto_register_subtree_array(subtrees, 1);
}

}  // namespace

void register_serial_link_types() {
  g_fields.proto = proto_register_protocol("pvtap serial records", "pvtap serial", "pvtap_serial");
  register_waiting_fields();
  g_serial_handle = register_dissector("pvtap_serial", dissect_serial, g_fields.proto);
  module_t* module = prefs_register_protocol(g_fields.proto, claim_serial_payloads);
  // The DLT_USER table sets its own handle for USER0-15 whenever its preferences are applied,
  // which may come after ours: the claim is made again before each file is dissected.
  register_init_routine(claim_serial_payloads);
  prefs_register_bool_preference(
      module, "user_link_types", "Dissect USER0-USER15 as serial bus records",
      "Link types USER0 to USER15 (DLT 147-162), which serial sniffers write: each record is "
      "bytes read from the bus, reassembled into frames across records. Turn off to leave them "
      "to the user DLT table (Preferences > Protocols > DLT_USER)",
      &g_claim_serial_payloads);
}

void claim_serial_link_types() {
  claim_serial_payloads();
  dissector_add_for_decode_as("rtacser.data", g_serial_handle);
}

}  // namespace pvtap::dissector
