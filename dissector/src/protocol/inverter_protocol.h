// InverterProtocol: the ids, handles and settings of one of the plugin's two protocols.
#pragma once

#include <epan/expert.h>
#include <epan/packet.h>

#include <array>

#include "plan/modbus_plan.h"
#include "pvtap/codec/dialect.h"
#include "wireshark_api/preference_types.h"

namespace pvtap::dissector {

// CommonFields: ids of the fields that frames of every dialect of a protocol may carry.
struct CommonFields {
  int dialect = -1;
  int role = -1;
  int station = -1;
  int function = -1;
  int start = -1;
  int count = -1;
  int byte_count = -1;
  int device = -1;
  int device_type = -1;
  int device_serial = -1;
  int exception_code = -1;
  int error_body = -1;  // the fixed body of a Hybrid error reply
  int word = -1;        // a data word no register map entry covers
  int undecoded = -1;   // data or body not decoded: a bad check, or a frame that did not parse
  int check = -1;
  int check_status = -1;
  int check_expected = -1;
  int noise = -1;
  int unknown_function = -1;
  int request_in = -1;
  int response_in = -1;
  int unanswered_request = -1;  // the request a timeout announcement is about
  int timeout_in = -1;          // on a request: the packet that announced its timeout
  int response_time = -1;
  int expected_count = -1;
  // The Modbus fields (invrtu only), by ModbusField.
  std::array<int, kModbusFieldCount> modbus = [] {
    std::array<int, kModbusFieldCount> ids{};
    ids.fill(-1);
    return ids;
  }();
};

// ExpertFields: the expert infos a protocol raises.
struct ExpertFields {
  expert_field bad_check = EI_INIT;
  expert_field malformed = EI_INIT;
  expert_field noise = EI_INIT;
  expert_field unknown_function = EI_INIT;
  expert_field exception = EI_INIT;
  expert_field unanswered = EI_INIT;
  expert_field unsolicited = EI_INIT;
  expert_field late_reply = EI_INIT;
  expert_field duplicate = EI_INIT;
  expert_field address_conflict = EI_INIT;
  expert_field echo = EI_INIT;
  expert_field collision = EI_INIT;
  expert_field count_mismatch = EI_INIT;
  expert_field role_corrected = EI_INIT;
  expert_field start_unknown = EI_INIT;
  expert_field start_assumed = EI_INIT;
  expert_field value_note = EI_INIT;
  expert_field value_suspicious = EI_INIT;
  expert_field quantity_problem = EI_INIT;
  expert_field dialect_changed = EI_INIT;
  expert_field broadcast_not_allowed = EI_INIT;
  expert_field write_count_problem = EI_INIT;
};

// Subtrees: the ett ids of a protocol's subtrees.
struct Subtrees {
  int frame = -1;
  int device = -1;
  int noise = -1;
  int coils = -1;
  int coil = -1;
  int device_object = -1;
  int map_entry = -1;  // a value of a station's own map
};

// ProtocolSettings: preference values; Wireshark writes them through pointers.
struct ProtocolSettings {
  PreferenceBool verify_check = true;
  PreferenceBool desegment = true;
  guint reply_timeout_ms = 1000;
  guint baud = 9600;          // of the bus behind the gateway: wire times of segments
  guint gateway_gap_ms = 50;  // silence between segments that proves a frame boundary
  gint gsl_ids = 0;           // GslIdReading, invrtu only
  gint pair_rule = 0;         // 0 binary, 1 decimal; invrtu only
};

// InverterProtocol: one protocol (invascii or invrtu) and everything registered for it.
struct InverterProtocol {
  const char* name;         // "Inverter RTU protocol"
  const char* short_name;   // "invRTU"
  const char* filter_name;  // "invrtu"
  const char* check_name;   // "CRC" or "Checksum"
  const char* check_key;    // "crc" or "checksum"
  const char* check_word;   // "CRC" or "checksum", inside sentences
  DialectSet dialects;
  int proto = -1;
  int tap = -1;
  CommonFields hf{};
  ExpertFields ei{};
  Subtrees ett{};
  ProtocolSettings settings{};
  dissector_handle_t stream_handle = nullptr;    // TCP: reassembles across segments
  dissector_handle_t datagram_handle = nullptr;  // UDP, records, RTAC serial payloads
};

InverterProtocol& rtu_protocol();
InverterProtocol& ascii_protocol();
InverterProtocol& protocol_of(Dialect d);

}  // namespace pvtap::dissector
