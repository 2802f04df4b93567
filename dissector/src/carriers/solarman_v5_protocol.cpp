#include "carriers/solarman_v5_protocol.h"

#include <epan/proto.h>

#include "carriers/solarman_v5_entry.h"
#include "fields/field_list.h"
#include "pvtap/carriers/solarman_v5_frame.h"

namespace pvtap::dissector {
namespace {

namespace v5 = solarman_v5;

const value_string kControlNames[] = {
    {v5::control::kRequest, "Modbus RTU request"},
    {v5::control::kResponse, "Modbus RTU response"},
    {v5::control::kHandshake, "Handshake"},
    {v5::control::kDataReport, "Data report"},
    {v5::control::kWifiInfo, "Wi-Fi info"},
    {v5::control::kHeartbeat, "Heartbeat"},
    {v5::control::kReport, "Report"},
    {v5::control::kHandshake - v5::control::kReplyOffset, "Handshake reply"},
    {v5::control::kDataReport - v5::control::kReplyOffset, "Data report reply"},
    {v5::control::kWifiInfo - v5::control::kReplyOffset, "Wi-Fi info reply"},
    {v5::control::kHeartbeat - v5::control::kReplyOffset, "Heartbeat reply"},
    {v5::control::kReport - v5::control::kReplyOffset, "Report reply"},
    {0, nullptr},
};

// FieldSpec: one invv5 field; abbrev relative to "invv5".
struct FieldSpec {
  int V5Fields::*id;
  const char* name;
  const char* abbrev;
  ftenum type;
  int display;
  const void* strings;
  const char* blurb;
};

const FieldSpec kFields[] = {
    {&V5Fields::length, "Payload length", "length", FT_UINT16, BASE_DEC, nullptr, nullptr},
    {&V5Fields::control, "Control code", "control", FT_UINT16, BASE_HEX, kControlNames, nullptr},
    {&V5Fields::sequence, "Sequence", "sequence", FT_UINT16, BASE_HEX, nullptr,
     "Low byte set by the client and echoed; high byte counted by the stick"},
    {&V5Fields::serial, "Logger serial", "serial", FT_UINT32, BASE_DEC, nullptr,
     "Serial number of the logger stick"},
    {&V5Fields::frame_type, "Frame type", "frame_type", FT_UINT8, BASE_HEX, nullptr, nullptr},
    {&V5Fields::sensor_type, "Sensor type", "sensor_type", FT_UINT16, BASE_HEX, nullptr, nullptr},
    {&V5Fields::status, "Status", "status", FT_UINT8, BASE_HEX, nullptr, nullptr},
    {&V5Fields::total_working_time, "Total working time", "total_working_time", FT_UINT32, BASE_DEC,
     nullptr, nullptr},
    {&V5Fields::power_on_time, "Power-on time", "power_on_time", FT_UINT32, BASE_DEC, nullptr,
     nullptr},
    {&V5Fields::offset_time, "Offset time", "offset_time", FT_UINT32, BASE_DEC, nullptr, nullptr},
    {&V5Fields::payload, "Payload", "payload", FT_BYTES, BASE_NONE, nullptr, nullptr},
    {&V5Fields::rtu, "Modbus RTU frame", "rtu", FT_BYTES, BASE_NONE, nullptr,
     "The RTU frame the stick carries, dissected by invrtu"},
    {&V5Fields::quirk, "Extra bytes after the RTU CRC", "quirk", FT_BYTES, BASE_NONE, nullptr,
     "Two zero bytes some sticks append to a response"},
    {&V5Fields::checksum, "Checksum", "checksum", FT_UINT8, BASE_HEX, nullptr,
     "Sum of the bytes from the length to the payload's end, mod 256"},
    {&V5Fields::checksum_status, "Checksum status", "checksum.status", FT_UINT8, BASE_NONE,
     proto_checksum_vals, nullptr},
    {&V5Fields::broken, "Broken V5 frame", "broken", FT_BYTES, BASE_NONE, nullptr,
     "Bytes that start like a V5 frame but are none: truncated, or their length does not hold"},
    {&V5Fields::claimed_length, "Claimed frame size", "claimed_size", FT_UINT32, BASE_DEC, nullptr,
     "The size the broken frame's length field claims"},
    {&V5Fields::noise, "Not V5", "noise", FT_BYTES, BASE_NONE, nullptr,
     "Bytes of the flow that are no V5 frame"},
    {&V5Fields::stick_code, "Stick code", "stick_code", FT_UINT8, BASE_HEX, nullptr,
     "The stick's own code in place of an RTU frame (05: no reply from the bus; 06: the "
     "request named another logger serial)"},
};

struct ExpertSpec {
  expert_field V5Experts::*id;
  const char* name;
  int group;
  int severity;
  const char* summary;
};

const ExpertSpec kExperts[] = {
    {&V5Experts::bad_checksum, "checksum.bad", PI_CHECKSUM, PI_ERROR, "Bad V5 checksum"},
    {&V5Experts::truncated, "truncated", PI_MALFORMED, PI_ERROR, "Truncated V5 frame"},
    {&V5Experts::length_mismatch, "length_mismatch", PI_MALFORMED, PI_ERROR,
     "V5 length does not hold"},
    {&V5Experts::payload_short, "payload_short", PI_MALFORMED, PI_ERROR,
     "V5 payload shorter than its fixed fields"},
    {&V5Experts::quirk, "quirk_found", PI_PROTOCOL, PI_NOTE,
     "Two zero bytes after the RTU CRC (a known stick quirk)"},
    {&V5Experts::noise, "not_v5", PI_UNDECODED, PI_WARN, "Bytes that are no V5 frame"},
    {&V5Experts::stick_no_reply, "stick_no_reply", PI_RESPONSE_CODE, PI_WARN,
     "The stick answered code 05: no reply from the bus behind it (a timeout)"},
    {&V5Experts::stick_refused, "stick_refused", PI_RESPONSE_CODE, PI_WARN,
     "The stick refused a request addressed to another logger serial (code 06)"},
    {&V5Experts::stick_code, "stick_code_other", PI_RESPONSE_CODE, PI_NOTE,
     "The stick answered a code in place of an RTU frame"},
};

}  // namespace

SolarmanV5Protocol& v5_protocol() {
  static SolarmanV5Protocol p;
  return p;
}

const char* v5_control_name(std::uint16_t control) {
  return val_to_str_const(control, kControlNames, "Unknown control code");
}

void register_v5_protocol() {
  SolarmanV5Protocol& p = v5_protocol();
  p.proto = proto_register_protocol("Solarman V5 (logger stick)", "invV5", "invv5");
  FieldList fields;
  for (const FieldSpec& f : kFields) {
    fields.add(&(p.hf.*f.id), f.name, std::string("invv5.") + f.abbrev, f.type, f.display,
               f.strings, 0, f.blurb != nullptr ? f.blurb : "");
  }
  fields.register_all(p.proto);
  ExpertList experts;
  for (const ExpertSpec& e : kExperts) {
    experts.add(&(p.ei.*e.id), std::string("invv5.") + e.name, e.group, e.severity, e.summary);
  }
  experts.register_all(p.proto);
  static int* subtrees[] = {&p.ett_frame};
  proto_register_subtree_array(subtrees, 1);
  p.handle = register_dissector("invv5", dissect_v5_tcp, p.proto);
}

void register_v5_handoff() {
  SolarmanV5Protocol& p = v5_protocol();
  // Port 8899 is only a hint: sticks are reached through NAT and forwards, so the heuristic
  // recognises them by structure; the (empty) port preference serves Decode As.
  dissector_add_uint_range_with_preference("tcp.port", "", p.handle);
  heur_dissector_add("tcp", v5_tcp_heuristic, "Solarman V5 over TCP", "invv5_tcp", p.proto,
                     HEURISTIC_ENABLE);
}

}  // namespace pvtap::dissector
