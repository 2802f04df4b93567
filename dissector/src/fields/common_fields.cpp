#include "fields/common_fields.h"

#include <string>

#include "fields/field_list.h"
#include "fields/value_tables.h"
#include "settings/register_maps.h"

namespace pvtap::dissector {
namespace {

// FieldSpec: one common field without value names; names are relative to the protocol's
// filter name.
struct FieldSpec {
  int CommonFields::*id;
  const char* name;
  const char* abbrev;
  ftenum type;
  int display;
  bool rtu_only;
  const char* blurb;
};

constexpr FieldSpec kFields[] = {
    {&CommonFields::station, "Station", "station", FT_UINT8, BASE_DEC, false,
     "Address of the inverter"},
    {&CommonFields::start, "Start address", "start", FT_UINT16, BASE_HEX, false,
     "Wire address of the first register"},
    {&CommonFields::count, "Register count", "count", FT_UINT16, BASE_DEC, false, nullptr},
    {&CommonFields::byte_count, "Byte count", "byte_count", FT_UINT8, BASE_DEC, true, nullptr},
    {&CommonFields::device, "Device number", "device", FT_UINT32, BASE_HEX, true,
     "Hybrid device number: type code and serial number"},
    {&CommonFields::device_serial, "Device serial number", "device.serial", FT_UINT24, BASE_DEC,
     true, nullptr},
    {&CommonFields::error_body, "Error reply body", "error_body", FT_UINT32, BASE_HEX, true,
     "The fixed body of a Hybrid error reply (0x1000 0x00FF), not a register range"},
    {&CommonFields::word, "Unmapped word", "word", FT_UINT16, BASE_HEX, false,
     "A data word that no register map entry covers"},
    {&CommonFields::undecoded, "Data, not decoded", "undecoded", FT_BYTES, BASE_NONE, false,
     "A frame's data or body, not decoded because its check failed or it did not parse"},
    {&CommonFields::noise, "Noise", "noise", FT_BYTES, BASE_NONE, false,
     "Bytes that belong to no frame"},
    {&CommonFields::unknown_function, "Unknown function code", "unknown_function", FT_UINT8,
     BASE_HEX, true, "Function code of a frame with a good CRC that no dialect defines"},
    {&CommonFields::response_time, "Response time", "response_time", FT_RELATIVE_TIME, BASE_NONE,
     false, "Time from the request to this response"},
    {&CommonFields::expected_count, "Expected count", "expected_count", FT_UINT16, BASE_DEC, false,
     "What the request asked for (bytes; words in the ASCII dialect)"},
};

// ExpertSpec: one expert info; names are relative to the protocol's filter name.
struct ExpertSpec {
  expert_field ExpertFields::*id;
  const char* name;
  int group;
  int severity;
  const char* summary;
};

constexpr ExpertSpec kExperts[] = {
    {&ExpertFields::malformed, "malformed", PI_MALFORMED, PI_ERROR, "Malformed frame"},
    {&ExpertFields::noise, "noise_run", PI_PROTOCOL, PI_WARN, "Bytes that belong to no frame"},
    {&ExpertFields::unknown_function, "unknown_function_frame", PI_PROTOCOL, PI_WARN,
     "Frame with an unknown function code"},
    {&ExpertFields::exception, "exception", PI_RESPONSE_CODE, PI_NOTE, "Exception reply"},
    {&ExpertFields::unanswered, "unanswered", PI_SEQUENCE, PI_WARN, "Request never answered"},
    {&ExpertFields::unsolicited, "unsolicited", PI_SEQUENCE, PI_WARN, "Reply with no request"},
    {&ExpertFields::late_reply, "late_reply", PI_SEQUENCE, PI_WARN,
     "Reply after its request timed out"},
    {&ExpertFields::duplicate, "duplicate", PI_SEQUENCE, PI_NOTE, "Duplicate reply"},
    {&ExpertFields::address_conflict, "address_conflict", PI_SEQUENCE, PI_WARN,
     "Address conflict: a second reply with other contents"},
    {&ExpertFields::echo, "echo", PI_SEQUENCE, PI_NOTE,
     "Echo of a request: the tap's adapter repeating it"},
    {&ExpertFields::collision, "collision", PI_SEQUENCE, PI_WARN,
     "Collision: two transmissions at once on a bus of more than one master"},
    {&ExpertFields::count_mismatch, "count_mismatch", PI_PROTOCOL, PI_WARN,
     "Byte count disagrees with the request"},
    {&ExpertFields::role_corrected, "role_corrected", PI_SEQUENCE, PI_NOTE,
     "Frame is the echo of a write request"},
    {&ExpertFields::start_unknown, "start_unknown", PI_UNDECODED, PI_NOTE,
     "Register words without a known start address"},
    {&ExpertFields::start_assumed, "start_assumed", PI_ASSUMPTION, PI_NOTE,
     "Start address assumed"},
    {&ExpertFields::value_note, "value_note", PI_PROTOCOL, PI_NOTE, "Register value note"},
    {&ExpertFields::value_suspicious, "value_suspicious", PI_PROTOCOL, PI_WARN,
     "Suspicious register value"},
};

std::string name_in(const InverterProtocol& p, const char* relative) {
  return std::string(p.filter_name) + "." + relative;
}

const value_string* device_type_names() {
  const RegisterDef* def = effective_map(Dialect::Hybrid).find_kind(RegisterKind::DeviceNumber);
  return def != nullptr ? register_value_names(*def) : nullptr;
}

void add_special_fields(InverterProtocol& p, bool rtu, FieldList& list) {
  CommonFields& hf = p.hf;
  const std::string check = name_in(p, p.check_key);
  list.add(&hf.check, p.check_name, check, FT_UINT16, BASE_HEX);
  list.add(&hf.check_status, std::string(p.check_name) + " status", check + ".status", FT_UINT8,
           BASE_NONE, VALS(proto_checksum_vals));
  list.add(&hf.check_expected, std::string("Expected ") + p.check_word, check + ".expected",
           FT_UINT16, BASE_HEX, nullptr, 0, "The value a correct frame would carry");
  list.add(&hf.request_in, "Request in frame", name_in(p, "request_in"), FT_FRAMENUM, BASE_NONE,
           FRAMENUM_TYPE(FT_FRAMENUM_REQUEST));
  list.add(&hf.response_in, "Response in frame", name_in(p, "response_in"), FT_FRAMENUM, BASE_NONE,
           FRAMENUM_TYPE(FT_FRAMENUM_RESPONSE));
  list.add(&hf.unanswered_request, "Unanswered request in frame", name_in(p, "unanswered_request"),
           FT_FRAMENUM, BASE_NONE, FRAMENUM_TYPE(FT_FRAMENUM_REQUEST), 0,
           "The request this packet's timeout announcement is about");
  list.add(&hf.timeout_in, "Timeout announced in frame", name_in(p, "timeout_in"), FT_FRAMENUM,
           BASE_NONE, nullptr, 0, "The packet that showed that this request got no reply");
  list.add(&hf.dialect, "Dialect", name_in(p, "dialect"), FT_UINT8, BASE_DEC,
           VALS(dialect_names()));
  list.add(&hf.role, "Role", name_in(p, "role"), FT_UINT8, BASE_DEC, VALS(role_names()));
  list.add(&hf.function, "Function", name_in(p, "function"), FT_UINT8, BASE_HEX,
           VALS(function_names(p.dialects)));
  if (!rtu) return;
  list.add(&hf.exception_code, "Exception code", name_in(p, "exception_code"), FT_UINT8, BASE_DEC,
           VALS(exception_names()));
  list.add(&hf.device_type, "Device type code", name_in(p, "device.type"), FT_UINT8, BASE_HEX,
           VALS(device_type_names()));
}

void register_fields(InverterProtocol& p) {
  const bool rtu = p.dialects.rtu();
  FieldList fields;
  for (const FieldSpec& f : kFields) {
    if (f.rtu_only && !rtu) continue;
    fields.add(&(p.hf.*f.id), f.name, name_in(p, f.abbrev), f.type, f.display, nullptr, 0,
               f.blurb != nullptr ? f.blurb : "");
  }
  add_special_fields(p, rtu, fields);
  fields.register_all(p.proto);
}

void register_experts(InverterProtocol& p) {
  ExpertList experts;
  experts.add(&p.ei.bad_check, name_in(p, (std::string(p.check_key) + ".bad").c_str()), PI_CHECKSUM,
              PI_WARN, std::string("Bad ") + p.check_word);
  for (const ExpertSpec& e : kExperts) {
    experts.add(&(p.ei.*e.id), name_in(p, e.name), e.group, e.severity, e.summary);
  }
  experts.register_all(p.proto);
}

}  // namespace

void register_common_items(InverterProtocol& p) {
  register_fields(p);
  register_experts(p);
  gint* etts[] = {&p.ett.frame, &p.ett.device, &p.ett.noise};
  proto_register_subtree_array(etts, G_N_ELEMENTS(etts));
}

}  // namespace pvtap::dissector
