#include "fields/common_fields.h"

#include <string>
#include <string_view>

#include "fields/field_list.h"
#include "fields/value_tables.h"
#include "settings/register_maps.h"

namespace pvtap::dissector {
namespace {

// Names: the value names a line of PVTAP_FRAME_FIELDS shows.
enum class Names : std::uint8_t {
  None,
  Dialects,
  Roles,
  Functions,  // those of the protocol's dialects
  Exceptions,
  DeviceTypes,  // Hybrid's device type codes
  CheckStatus,
  RequestFrame,  // a link to a request: Wireshark draws it so
  ResponseFrame,
};

// Protocols: which protocols register a field.
enum class Protocols : std::uint8_t { All, Rtu };

// FieldRow: a line of PVTAP_FRAME_FIELDS.
struct FieldRow {
  TreeField id;
  const char* name;
  const char* abbrev;
  ftenum type;
  int display;
  Names names;
  Protocols protocols;
  const char* blurb;
};

#define PVTAP_FIELD_ROW(id, name, abbrev, type, display, names, protocols, blurb) \
  {TreeField::id, name, abbrev, type, display, Names::names, Protocols::protocols, blurb},
constexpr FieldRow kFields[] = {PVTAP_FRAME_FIELDS(PVTAP_FIELD_ROW)};
#undef PVTAP_FIELD_ROW

constexpr ExpertRow kExperts[] = {PVTAP_FRAME_EXPERTS(PVTAP_EXPERT_ROW)};

// SubtreeRow: a line of PVTAP_SUBTREES.
struct SubtreeRow {
  Subtree id;
  Protocols protocols;
};

#define PVTAP_SUBTREE_ROW(id, protocols) {Subtree::id, Protocols::protocols},
constexpr SubtreeRow kSubtrees[] = {PVTAP_SUBTREES(PVTAP_SUBTREE_ROW)};
#undef PVTAP_SUBTREE_ROW

const value_string* device_type_names() {
  const RegisterDef* def = effective_map(Dialect::Hybrid).find_kind(RegisterKind::DeviceNumber);
  return def != nullptr ? register_value_names(*def) : nullptr;
}

// Made only for the fields a protocol registers: the device types read the Hybrid map.
const void* value_names(Names names, const InverterProtocol& p) {
  switch (names) {
    case Names::Dialects:
      return VALS(dialect_names());
    case Names::Roles:
      return VALS(role_names());
    case Names::Functions:
      return VALS(function_names(p.dialects));
    case Names::Exceptions:
      return VALS(exception_names());
    case Names::DeviceTypes:
      return VALS(device_type_names());
    case Names::CheckStatus:
      return VALS(proto_checksum_vals);
    case Names::RequestFrame:
      return FRAMENUM_TYPE(FT_FRAMENUM_REQUEST);
    case Names::ResponseFrame:
      return FRAMENUM_TYPE(FT_FRAMENUM_RESPONSE);
    case Names::None:
      break;
  }
  return nullptr;
}

// Puts `word` in place of each `marker` in `text`.
void put(std::string& text, std::string_view marker, std::string_view word) {
  for (auto at = text.find(marker); at != std::string::npos;
       at = text.find(marker, at + word.size())) {
    text.replace(at, marker.size(), word);
  }
}

// A table's text with the protocol's words for its check (plan/field_table.h says which).
std::string spelled(const char* text, const InverterProtocol& p, const char* word) {
  std::string out(text);
  put(out, "{Check}", p.check_name);
  put(out, "{check}", word);
  return out;
}

std::string name_of(const char* text, const InverterProtocol& p) {
  return spelled(text, p, p.check_word);
}

std::string abbrev_of(const char* text, const InverterProtocol& p) {
  return std::string(p.filter_name) + "." + spelled(text, p, p.check_key);
}

void register_fields(InverterProtocol& p) {
  const bool rtu = p.dialects.rtu();
  FieldList fields;
  for (const FieldRow& f : kFields) {
    if (f.protocols == Protocols::Rtu && !rtu) continue;
    fields.add(&p.hf.frame[static_cast<std::size_t>(f.id)], name_of(f.name, p),
               abbrev_of(f.abbrev, p), f.type, f.display, value_names(f.names, p), 0,
               f.blurb != nullptr ? f.blurb : "");
  }
  fields.register_all(p.proto);
}

void register_experts(InverterProtocol& p) {
  ExpertList experts;
  for (const ExpertRow& e : kExperts) {
    experts.add(p.ei.of(e.id), abbrev_of(e.abbrev, p), e.group, e.severity, name_of(e.summary, p));
  }
  experts.register_all(p.proto);
}

// invrtu's Modbus subtrees are registered here too, before its Modbus fields: subtree ids
// are counted apart from field ids, so that no id moves.
void register_subtrees(InverterProtocol& p) {
  gint* etts[kSubtreeCount] = {};
  int count = 0;
  for (const SubtreeRow& s : kSubtrees) {
    if (s.protocols == Protocols::Rtu && !p.dialects.rtu()) continue;
    etts[count++] = &p.ett.all[static_cast<std::size_t>(s.id)];
  }
  proto_register_subtree_array(etts, count);
}

}  // namespace

void register_common_items(InverterProtocol& p) {
  register_fields(p);
  register_experts(p);
  register_subtrees(p);
}

}  // namespace pvtap::dissector
