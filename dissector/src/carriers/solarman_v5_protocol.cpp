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

// V5FieldRow: a line of PVTAP_V5_FIELDS.
struct V5FieldRow {
  V5Field id;
  const char* name;
  const char* abbrev;
  ftenum type;
  int display;
  const void* strings;
  const char* blurb;
};

#define PVTAP_V5_FIELD_ROW(id, name, abbrev, type, display, strings, blurb) \
  {V5Field::id, name, abbrev, type, display, strings, blurb},
const V5FieldRow kFields[] = {PVTAP_V5_FIELDS(PVTAP_V5_FIELD_ROW)};
#undef PVTAP_V5_FIELD_ROW

using V5ExpertRow = ExpertRowOf<V5Expert>;  // a line of PVTAP_V5_EXPERTS
#define PVTAP_V5_EXPERT_ROW(id, abbrev, group, severity, summary) \
  {V5Expert::id, abbrev, group, severity, summary},
const V5ExpertRow kExperts[] = {PVTAP_V5_EXPERTS(PVTAP_V5_EXPERT_ROW)};
#undef PVTAP_V5_EXPERT_ROW

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
  for (const V5FieldRow& f : kFields) {
    fields.add(&p.hf[static_cast<std::size_t>(f.id)], f.name, std::string("invv5.") + f.abbrev,
               f.type, f.display, f.strings, 0, f.blurb != nullptr ? f.blurb : "");
  }
  fields.register_all(p.proto);
  ExpertList experts;
  for (const V5ExpertRow& e : kExperts) {
    experts.add(p.expert(e.id), std::string("invv5.") + e.abbrev, e.group, e.severity, e.summary);
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
