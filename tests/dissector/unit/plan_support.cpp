#include "plan_support.h"

#include <iterator>
#include <sstream>

namespace pvtap::dissector::test {
namespace {

void write_value(std::ostream& out, const TreeItem& item) {
  switch (item.type) {
    case ValueType::Bytes:
      return;
    case ValueType::Uint:
      out << " = " << item.uint;
      return;
    case ValueType::Boolean:
      out << " = bit " << unsigned{item.bit} << " of " << item.uint;
      return;
    case ValueType::Double:
      out << " = " << item.number;
      return;
    case ValueType::String:
      out << " = '" << item.string << "'";
      return;
    case ValueType::Time:
      out << " = " << item.time.secs << " s " << item.time.nsecs << " ns";
      return;
  }
}

const char* subtree_name(Subtree s) {
  switch (s) {
    case Subtree::Frame:
      return " {frame}";
    case Subtree::Noise:
      return " {noise}";
    case Subtree::Device:
      return " {device}";
    case Subtree::Flags:
      return " {flags}";
    case Subtree::Coils:
      return " {coils}";
    case Subtree::Coil:
      return " {coil}";
    case Subtree::DeviceObject:
      return " {object}";
    case Subtree::MapEntry:
      return " {map entry}";
    case Subtree::None:
      break;
  }
  return "";
}

// A field worked out rather than read has no place; an expert info's item always shows one.
void write_place(std::ostream& out, const TreeItem& item) {
  if (item.kind == ItemKind::Field && item.offset == 0 && item.length == 0) return;
  out << " [" << item.offset << "+" << item.length << "]";
}

// The generic fields of a station map's entries by name, other Modbus fields by number.
void write_modbus_field(std::ostream& out, ModbusField field) {
  switch (field) {
    case ModbusField::MapValue:
      out << ".MapValue";
      return;
    case ModbusField::MapKey:
      out << ".MapKey";
      return;
    case ModbusField::MapNumber:
      out << ".MapNumber";
      return;
    default:
      out << "." << static_cast<unsigned>(field);
  }
}

void write_field(std::ostream& out, const TreeItem& item) {
  out << unsigned{item.depth} << " " << name_of(item.field);
  if (item.field == TreeField::Modbus) write_modbus_field(out, item.modbus);
  if (item.def != nullptr) out << " " << item.def->key;
  write_place(out, item);
  write_value(out, item);
  if (item.form == LabelForm::Value) out << " \"" << item.text << "\"";
  if (item.form == LabelForm::Whole) out << " label \"" << item.text << "\"";
  if (item.generated) out << " (generated)";
  if (item.appended != nullptr) out << " +\"" << item.appended << "\"";
  out << subtree_name(item.subtree);
}

void write_expert(std::ostream& out, const TreeItem& item) {
  if (item.kind == ItemKind::Expert) {
    out << "  ! " << name_of(item.expert) << " on #" << item.target;
  } else {
    out << unsigned{item.depth} << " ! " << name_of(item.expert);
    write_place(out, item);
  }
  out << ": " << (item.text != nullptr ? item.text : "(summary)");
  if (item.appended != nullptr) out << " +\"" << item.appended << "\"";
}

}  // namespace

std::vector<std::string> lines_of(const TreeDescription& description) {
  std::vector<std::string> lines;
  for (const TreeItem& item : description) {
    std::ostringstream line;
    if (item.kind == ItemKind::Field) {
      write_field(line, item);
    } else {
      write_expert(line, item);
    }
    lines.push_back(line.str());
  }
  return lines;
}

#define PVTAP_NAME(id, ...) #id,

const char* name_of(TreeField field) {
  static constexpr const char* kNames[] = {PVTAP_FRAME_FIELDS(PVTAP_NAME) "None", "Protocol",
                                           "RegisterValue", "RegisterFlag", "Modbus"};
  static_assert(std::size(kNames) == static_cast<std::size_t>(TreeField::Modbus) + 1);
  const auto i = static_cast<std::size_t>(field);
  return i < std::size(kNames) ? kNames[i] : "?";
}

const char* name_of(TreeExpert expert) {
  static constexpr const char* kNames[] = {PVTAP_FRAME_EXPERTS(PVTAP_NAME)
                                               PVTAP_MODBUS_EXPERTS(PVTAP_NAME) "None"};
  static_assert(std::size(kNames) == static_cast<std::size_t>(TreeExpert::None) + 1);
  const auto i = static_cast<std::size_t>(expert);
  return i < std::size(kNames) ? kNames[i] : "?";
}

#undef PVTAP_NAME

}  // namespace pvtap::dissector::test
