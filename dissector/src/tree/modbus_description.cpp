#include "tree/modbus_description.h"

#include <string>

#include "pvtap/codec/function_codes.h"

namespace pvtap::dissector {
namespace {

TreeItem modbus_item(ModbusField field, FieldSpan s, std::uint8_t depth) {
  TreeItem item;
  item.field = TreeField::Modbus;
  item.modbus = field;
  item.depth = depth;
  item.offset = s.offset;
  item.length = s.length;
  return item;
}

std::uint32_t add_generated(Builder& b, ModbusField field, std::uint32_t value) {
  TreeItem item = modbus_item(field, FieldSpan{}, kFrame);
  item.uint = value;
  item.generated = true;
  return b.add(item);
}

void add_field(Builder& b, const PlannedField& f) {
  TreeItem item = modbus_item(f.field, f.span, kFrame);
  switch (f.kind) {
    case PlannedKind::Uint:
      item.uint = f.value;
      if (f.text != nullptr) {
        item.form = LabelForm::Value;
        item.text = f.text;
      }
      break;
    case PlannedKind::Bytes:
      item.type = ValueType::Bytes;
      break;
    case PlannedKind::String:
      item.type = ValueType::String;
      item.string = f.text;
      break;
  }
  b.add(item);
}

const char* on_off(bool on) {
  return on ? "on" : "off";
}

// One item per bit, "coil 17: on", with its state beneath it; bits of a reply whose request
// is not known show only their state.
void add_bits(Builder& b, const ModbusPlan& m) {
  if (m.bit_count == 0) return;
  const char* what = m.inputs ? "input" : "coil";
  TreeItem group = modbus_item(ModbusField::Coils, m.bits_span, kFrame);
  group.type = ValueType::Bytes;
  group.subtree = Subtree::Coils;
  group.appended = b.text(" (" + std::to_string(m.bit_count) + (m.inputs ? " inputs)" : " coils)"));
  b.add(group);
  const ModbusField address = m.inputs ? ModbusField::InputAddress : ModbusField::CoilAddress;
  const ModbusField state = m.inputs ? ModbusField::InputState : ModbusField::CoilState;
  for (std::size_t i = 0; i < m.bit_count; ++i) {
    const PlannedBit& bit = m.bits[i];
    std::uint8_t depth = kField;
    if (m.bits_placed) {
      TreeItem item = modbus_item(address, bit.span, kField);
      item.uint = bit.address;
      item.form = LabelForm::Whole;
      item.text =
          b.text(std::string(what) + " " + std::to_string(bit.address) + ": " + on_off(bit.on));
      item.subtree = Subtree::Coil;
      b.add(item);
      depth = kField + 1;
    }
    TreeItem on = modbus_item(state, bit.span, depth);
    on.type = ValueType::Boolean;
    on.uint = bit.on ? 1 : 0;
    b.add(on);
  }
}

ModbusField object_field(std::uint8_t id) {
  switch (id) {
    case 0x00:
      return ModbusField::Vendor;
    case 0x01:
      return ModbusField::Product;
    case 0x02:
      return ModbusField::Revision;
    default:
      return ModbusField::ObjectValue;
  }
}

void add_objects(Builder& b, const ModbusPlan& m) {
  for (std::size_t i = 0; i < m.object_count; ++i) {
    const PlannedObject& o = m.objects[i];
    TreeItem item = modbus_item(object_field(o.id), o.span, kFrame);
    item.type = ValueType::String;
    item.string = o.value;
    item.form = LabelForm::Whole;
    item.text = b.text(std::string(text_of(o.name)) + ": " + std::string(text_of(o.value)));
    item.subtree = Subtree::DeviceObject;
    b.add(item);
    TreeItem id = modbus_item(ModbusField::Object, FieldSpan{o.span.offset, 1}, kField);
    id.uint = o.id;
    b.add(id);
  }
}

std::string dialect_text(Dialect d) {
  return std::string(dialect_short_title(d));
}

void add_quantity_problem(Builder& b, const FrameRecord& r) {
  if (!r.quantity_problem) return;
  add_generated(b, ModbusField::QuantityMin, r.quantity_min);
  const std::uint32_t max = add_generated(b, ModbusField::QuantityMax, r.quantity_max);
  const char* what = r.quantity_write_part ? "writes" : "asks for";
  b.expert_on(max, TreeExpert::QuantityProblem,
              "The request " + std::string(what) + " a quantity of " +
                  std::to_string(r.quantity_found) + "; the specification allows " +
                  std::to_string(r.quantity_min) + " to " + std::to_string(r.quantity_max));
}

void add_dialect_change(Builder& b, const FramePlan& plan, const FrameRecord& r) {
  if (!r.dialect_changed) return;
  const std::uint32_t item = add_generated(b, ModbusField::PreviousDialect,
                                           static_cast<std::uint32_t>(r.previous_dialect));
  b.expert_on(item, TreeExpert::DialectChanged,
              "Station " + std::to_string(plan.station) + " spoke " +
                  dialect_text(r.previous_dialect) + " until this frame, now " +
                  dialect_text(plan.dialect));
}

}  // namespace

void add_station_name(Builder& b, const FramePlan& plan) {
  if (plan.station_name == nullptr) return;
  TreeItem item = modbus_item(ModbusField::StationName, FieldSpan{}, kFrame);
  item.type = ValueType::String;
  item.string = plan.station_name;
  item.generated = true;
  b.add(item);
}

void add_modbus_fields(Builder& b, const FramePlan& plan) {
  const ModbusPlan& m = plan.modbus;
  for (std::size_t i = 0; i < m.field_count; ++i) add_field(b, m.fields[i]);
  add_bits(b, m);
  add_objects(b, m);
}

void add_station_findings(Builder& b, const FramePlan& plan, const FrameRecord& record) {
  // All of them are invrtu's own items (PVTAP_MODBUS_FIELDS and _EXPERTS), which invascii
  // never registers: a frame it shows gets none (fuzz finding 11, a station's change of
  // dialect to ASCII named an unregistered expert info).
  if (!rtu_framed(plan.dialect)) return;
  add_quantity_problem(b, record);
  if (record.broadcast_not_allowed) {
    b.expert_item(TreeExpert::BroadcastNotAllowed, FieldSpan{},
                  "A request broadcast to address 0, which only writes may use: no station "
                  "answers it");
  }
  if (record.write_count_problem) {
    b.expert_item(TreeExpert::WriteCountProblem, FieldSpan{},
                  b.text("The quantity written needs a byte count of " +
                         std::to_string(record.write_count_expected)));
  }
  add_dialect_change(b, plan, record);
}

}  // namespace pvtap::dissector
