#include "tree/value_description.h"

#include <string>
#include <string_view>

#include "fields/register_field_type.h"
#include "pvtap/registers/register_format.h"

namespace pvtap::dissector {
namespace {

// Warnings that point at a probable error in the data rather than a gap in the map.
constexpr auto kSuspicious =
    static_cast<std::uint16_t>(static_cast<unsigned>(ValueWarning::LowPartOver9999) |
                               static_cast<unsigned>(ValueWarning::InvalidBcd) |
                               static_cast<unsigned>(ValueWarning::InvalidDate));

void add_value_warnings(Builder& b, std::uint32_t item, const PlannedValue& v) {
  for (unsigned bit = 0; bit < 16; ++bit) {
    const auto w = static_cast<std::uint16_t>(1u << bit);
    if ((v.warnings & w) == 0) continue;
    const std::string_view why = describe(static_cast<ValueWarning>(w));
    const TreeExpert expert =
        (w & kSuspicious) != 0 ? TreeExpert::ValueSuspicious : TreeExpert::ValueNote;
    b.expert_on(item, expert, std::string(text_of(v.label)) + ": " + std::string(why));
  }
}

// The named flags of a bits register, one item each in bit order.
void add_flags(Builder& b, const PlannedValue& v) {
  unsigned named = 0;
  for (const BitName& named_bit : v.def->bits) {
    if (named_bit.index < 16 && !named_bit.name.empty()) named |= 1u << named_bit.index;
  }
  for (std::uint8_t bit = 0; bit < 16; ++bit) {
    if ((named & (1u << bit)) == 0) continue;
    TreeItem flag;
    flag.field = TreeField::RegisterFlag;
    flag.type = ValueType::Boolean;
    flag.depth = kField;
    flag.offset = v.span.offset;
    flag.length = v.span.length;
    flag.uint = v.raw;
    flag.def = v.def;
    flag.bit = bit;
    b.add(flag);
  }
}

bool numeric(const RegisterDef& def) {
  return def.kind != RegisterKind::Text && def.kind != RegisterKind::BcdYearMonth;
}

// A value of a station's own map, which has no field of its own (Wireshark registers fields
// at start-up; the table of station maps changes at run time): the generic map fields, with
// the entry's key and, for numbers, the number under it.
std::uint32_t add_map_value(Builder& b, const PlannedValue& v) {
  TreeItem item;
  item.field = TreeField::Modbus;
  item.modbus = ModbusField::MapValue;
  item.type = ValueType::String;
  item.form = LabelForm::Whole;
  item.depth = kFrame;
  item.offset = v.span.offset;
  item.length = v.span.length;
  item.string = v.map_value;
  item.text = b.text(std::string(text_of(v.label)) + ": " + std::string(text_of(v.text)));
  item.subtree = Subtree::MapEntry;
  const std::uint32_t index = b.add(item);
  TreeItem key = item;
  key.modbus = ModbusField::MapKey;
  key.form = LabelForm::Default;
  key.depth = kField;
  key.string = v.map_key;
  key.text = nullptr;
  key.subtree = Subtree::None;
  key.generated = true;
  b.add(key);
  if (!numeric(*v.def)) return index;
  TreeItem number = key;
  number.modbus = ModbusField::MapNumber;
  number.type = ValueType::Double;
  number.generated = false;
  // Integer kinds (raw words, enumerations, bits) as their integer, the rest as shown.
  number.number = register_field_type(*v.def) == RegisterFieldType::Double
                      ? v.number
                      : static_cast<double>(v.raw);
  b.add(number);
  return index;
}

std::uint32_t add_value(Builder& b, const PlannedValue& v) {
  if (v.map_key != nullptr && v.def != nullptr) return add_map_value(b, v);
  TreeItem item;
  item.depth = kFrame;
  item.offset = v.span.offset;
  item.length = v.span.length;
  item.form = LabelForm::Whole;
  item.uint = v.raw;
  if (v.def == nullptr) {
    item.field = TreeField::Word;
    item.text = b.text(std::string(text_of(v.label)) + ": " + std::string(text_of(v.text)) +
                       " (not in the register map)");
    return b.add(item);
  }
  item.field = TreeField::RegisterValue;
  item.def = v.def;
  item.text = b.text(std::string(text_of(v.label)) + ": " + std::string(text_of(v.text)));
  switch (register_field_type(*v.def)) {
    case RegisterFieldType::Double:
      item.type = ValueType::Double;
      item.number = v.number;
      break;
    case RegisterFieldType::String:
      item.type = ValueType::String;
      item.string = v.text;
      break;
    case RegisterFieldType::Uint16:
    case RegisterFieldType::Uint32:
      item.subtree = v.def->kind == RegisterKind::Bits ? Subtree::Flags : Subtree::None;
      break;
  }
  const std::uint32_t index = b.add(item);
  if (item.subtree == Subtree::Flags) add_flags(b, v);
  return index;
}

}  // namespace

void add_values(Builder& b, const FramePlan& plan) {
  for (std::size_t i = 0; i < plan.value_count; ++i) {
    const PlannedValue& v = plan.values[i];
    add_value_warnings(b, add_value(b, v), v);
  }
  if (plan.decode_note == nullptr) return;
  const TreeExpert expert =
      plan.start_assumed ? TreeExpert::StartAssumed : TreeExpert::StartUnknown;
  b.expert_item(expert, plan.layout.words, plan.decode_note);
}

}  // namespace pvtap::dissector
