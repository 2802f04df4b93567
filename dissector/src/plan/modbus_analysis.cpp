#include "plan/modbus_analysis.h"

#include <string>
#include <vector>

#include "pvtap/codec/device_identification.h"
#include "pvtap/codec/function_codes.h"
#include "pvtap/registers/coil_bits.h"

namespace pvtap::dissector {
namespace {

constexpr std::uint16_t kHeader = 2;  // station, function

FieldSpan span(std::size_t offset, std::size_t length) {
  return {static_cast<std::uint16_t>(offset), static_cast<std::uint16_t>(length)};
}

// The bytes of `data` lie last before the CRC in every Modbus frame that carries them.
std::size_t data_offset(const Frame& f, const FrameLayout& l) {
  return l.check.offset - f.data.size();
}

std::string hex(unsigned value, int digits) {
  static constexpr char kDigits[] = "0123456789ABCDEF";
  std::string out = "0x";
  for (int shift = (digits - 1) * 4; shift >= 0; shift -= 4)
    out += kDigits[(value >> shift) & 0xFu];
  return out;
}

// Collects the plan's fields and the Info column's detail, then copies them to the arena.
struct Collector {
  const Frame& f;
  const FrameLayout& layout;
  const Arena& arena;
  std::vector<PlannedField> fields;
  std::string detail;

  void uint(ModbusField field, FieldSpan s, std::uint32_t value, std::string_view text = {}) {
    fields.push_back(
        {field, PlannedKind::Uint, s, value, text.empty() ? nullptr : arena.copy(text)});
  }
  void bytes(ModbusField field, FieldSpan s) {
    if (s.present()) fields.push_back({field, PlannedKind::Bytes, s, 0, nullptr});
  }
  void string(ModbusField field, FieldSpan s, std::string_view text) {
    fields.push_back({field, PlannedKind::String, s, 0, arena.copy(text)});
  }
  FieldSpan data_span() const { return span(data_offset(f, layout), f.data.size()); }
};

void plan_diagnostics(Collector& c) {
  const std::uint16_t sub = *c.f.sub_function;
  const std::string_view name = fc::diagnostics_name(sub);
  const std::string shown =
      (name.empty() ? "unknown sub-function" : std::string(name)) + " (" + hex(sub, 4) + ")";
  c.uint(ModbusField::SubFunction, span(kHeader, 2), sub, shown);
  for (std::size_t i = 0; i < c.f.words.size(); ++i) {
    c.uint(ModbusField::DiagnosticsData, span(kHeader + 2 + 2 * i, 2), c.f.words[i]);
  }
  if (!c.f.data.empty()) c.bytes(ModbusField::DiagnosticsBytes, c.data_span());
  c.detail = name.empty() ? "sub-function " + hex(sub, 4) : std::string(name);
}

void plan_read_write(Collector& c) {
  c.uint(ModbusField::WriteStart, span(kHeader + 4, 2), *c.f.write_start);
  c.uint(ModbusField::WriteCount, span(kHeader + 6, 2), *c.f.write_count);
  c.detail = "read " + std::to_string(c.f.count.value_or(0)) + " from " +
             hex(c.f.start.value_or(0), 4) + ", write " + std::to_string(*c.f.write_count) +
             " to " + hex(*c.f.write_start, 4);
}

void plan_mask_write(Collector& c) {
  if (c.f.words.size() != 2) return;
  c.uint(ModbusField::AndMask, span(kHeader + 2, 2), c.f.words[0]);
  c.uint(ModbusField::OrMask, span(kHeader + 4, 2), c.f.words[1]);
  c.detail = "register " + hex(c.f.start.value_or(0), 4) + ", and " + hex(c.f.words[0], 4) +
             ", or " + hex(c.f.words[1], 4);
}

void plan_fifo(Collector& c) {
  if (c.f.role == Role::Request) {
    c.detail = "FIFO at " + hex(c.f.start.value_or(0), 4);
    return;
  }
  const std::uint16_t count = c.f.count.value_or(0);
  c.uint(ModbusField::FifoCount, span(kHeader + 2, 2), count);
  for (std::size_t i = 0; i < c.f.words.size(); ++i) {
    c.uint(ModbusField::FifoValue, span(kHeader + 4 + 2 * i, 2), c.f.words[i]);
  }
  c.detail = std::to_string(count) + (count == 1 ? " value" : " values") + " in the FIFO";
}

void plan_identification_request(Collector& c) {
  const std::size_t d = data_offset(c.f, c.layout);
  if (c.f.data.size() != 3) return;
  c.uint(ModbusField::ReadCode, span(d + 1, 1), c.f.data[1]);
  c.uint(ModbusField::Object, span(d + 2, 1), c.f.data[2],
         std::string(device_object_name(c.f.data[2])) + " (" + hex(c.f.data[2], 2) + ")");
  c.detail = "device identification from object " + hex(c.f.data[2], 2);
}

std::string device_text(const DeviceIdentification& id) {
  std::string out;
  for (const std::string_view part : {id.vendor(), id.product(), id.revision()}) {
    if (part.empty()) continue;
    if (!out.empty()) out += ' ';
    out += part;
  }
  return out;
}

void plan_objects(const DeviceIdentification& id, std::size_t d, const Frame& f, const Arena& arena,
                  ModbusPlan& m) {
  m.objects = arena.make_array<PlannedObject>(id.object_count);
  m.object_count = id.object_count;
  for (std::size_t i = 0; i < id.object_count; ++i) {
    const DeviceObject& o = id.objects[i];
    const std::size_t at =
        d + static_cast<std::size_t>(reinterpret_cast<const std::uint8_t*>(o.value.data()) -
                                     f.data.begin());
    m.objects[i] = {o.id, arena.copy(device_object_name(o.id)), arena.copy(o.value),
                    span(at - 2, o.value.size() + 2)};
  }
}

void plan_identification_reply(Collector& c, bool with_items, ModbusPlan& m) {
  const auto id = read_device_identification(c.f);
  if (!id) return;
  const std::size_t d = data_offset(c.f, c.layout);
  c.uint(ModbusField::ReadCode, span(d + 1, 1), id->read_code);
  c.uint(ModbusField::Conformity, span(d + 2, 1), id->conformity);
  c.uint(ModbusField::MoreFollows, span(d + 3, 1), id->more_follows ? 0xFF : 0x00);
  c.uint(ModbusField::NextObject, span(d + 4, 1), id->next_object);
  c.uint(ModbusField::ObjectCount, span(d + 5, 1), static_cast<std::uint32_t>(id->object_count));
  if (with_items) plan_objects(*id, d, c.f, c.arena, m);
  const std::string name = device_text(*id);
  c.detail = name.empty() ? std::to_string(id->object_count) + " objects" : name;
}

void plan_encapsulated(Collector& c, bool with_items, ModbusPlan& m) {
  if (c.f.data.empty()) return;
  const std::size_t d = data_offset(c.f, c.layout);
  c.uint(ModbusField::MeiType, span(d, 1), c.f.data[0]);
  if (c.f.data[0] != fc::kMeiDeviceIdentification) return;
  if (c.f.role == Role::Request) {
    plan_identification_request(c);
  } else {
    plan_identification_reply(c, with_items, m);
  }
}

void plan_server_id(Collector& c) {
  if (c.f.role != Role::Response) return;
  c.bytes(ModbusField::ServerData, c.data_span());
  const auto id = read_server_id(c.f);
  if (!id || id->text.empty()) return;
  const auto at = static_cast<std::size_t>(reinterpret_cast<const std::uint8_t*>(id->text.data()) -
                                           c.f.data.begin());
  c.string(ModbusField::ServerId, span(data_offset(c.f, c.layout) + at, id->text.size()), id->text);
  c.detail = std::string(id->text);
}

void plan_event_counter(Collector& c) {
  if (c.f.role != Role::Response || c.f.words.size() != 2) return;
  c.uint(ModbusField::EventStatus, span(kHeader, 2), c.f.words[0]);
  c.uint(ModbusField::EventCount, span(kHeader + 2, 2), c.f.words[1]);
  c.detail = std::to_string(c.f.words[1]) + " events";
}

void plan_exception_status(Collector& c) {
  if (c.f.role != Role::Response || c.f.data.size() != 1) return;
  c.uint(ModbusField::ExceptionStatus, c.data_span(), c.f.data[0]);
  c.detail = "status " + hex(c.f.data[0], 2);
}

void plan_bits(const CoilBits& bits, Collector& c, bool with_items, ModbusPlan& m) {
  const char* what = bits.inputs ? "inputs" : "coils";
  m.inputs = bits.inputs;
  m.bits_placed = bits.start.has_value();
  const bool single = c.f.function == fc::kWriteSingleCoil;
  const std::size_t first = single ? c.layout.words.offset : data_offset(c.f, c.layout);
  m.bits_span = single ? c.layout.words : c.data_span();
  if (single) {
    c.detail = "coil " + std::to_string(bits.start.value_or(0)) + (bits.on(0) ? " on" : " off");
  } else {
    c.detail = std::to_string(bits.count) + " " + what;
    if (bits.start) c.detail += " from " + std::to_string(*bits.start);
  }
  if (!with_items || bits.count == 0) return;
  m.bits = c.arena.make_array<PlannedBit>(bits.count);
  m.bit_count = bits.count;
  for (std::size_t i = 0; i < bits.count; ++i) {
    const auto address = static_cast<std::uint16_t>(bits.start.value_or(0) + i);
    m.bits[i] = {address, bits.on(i), single ? m.bits_span : span(first + i / 8, 1)};
  }
}

// A request for bits: the range it names.
void plan_bit_request(Collector& c) {
  const char* what = c.f.function == fc::kReadDiscreteInputs ? "inputs" : "coils";
  c.detail = std::to_string(c.f.count.value_or(0)) + " " + what + " from " +
             std::to_string(c.f.start.value_or(0));
}

void plan_function(Collector& c, const Frame* request, bool with_items, ModbusPlan& m) {
  const Frame& f = c.f;
  if (const auto bits = coil_bits(f, request)) {
    plan_bits(*bits, c, with_items, m);
    return;
  }
  switch (f.function) {
    case fc::kReadCoils:
    case fc::kReadDiscreteInputs:
    case fc::kWriteMultipleCoils:
      if (f.count && f.start) plan_bit_request(c);
      return;
    case fc::kDiagnostics:
      if (f.sub_function) plan_diagnostics(c);
      return;
    case fc::kReadWriteMultiple:
      if (f.write_start && f.write_count) plan_read_write(c);
      return;
    case fc::kMaskWriteRegister:
      return plan_mask_write(c);
    case fc::kReadFifoQueue:
      return plan_fifo(c);
    case fc::kEncapsulatedInterface:
      return plan_encapsulated(c, with_items, m);
    case fc::kReportServerId:
      return plan_server_id(c);
    case fc::kCommEventCounter:
      return plan_event_counter(c);
    case fc::kReadExceptionStatus:
      return plan_exception_status(c);
    case fc::kCommEventLog:
      if (f.role == Role::Response) c.bytes(ModbusField::EventLog, c.data_span());
      return;
    case fc::kReadFileRecord:
    case fc::kWriteFileRecord:
      c.bytes(ModbusField::FileRecords, c.data_span());
      c.detail = std::to_string(f.data.size()) + " bytes of file records";
      return;
    default:
      return;
  }
}

}  // namespace

void correct_modbus_layout(const Frame& f, FrameLayout& l) {
  // The 0x18 reply's count is the FIFO count, shown by a field of its own.
  const bool fifo_reply = f.function == fc::kReadFifoQueue && f.role == Role::Response;
  if (modbus_family(f.dialect) && !f.exception_code && fifo_reply) l.count = FieldSpan{};
}

void plan_modbus(const Frame& f, const Frame* request, bool with_items, const Arena& arena,
                 FramePlan& plan) {
  if (!modbus_family(f.dialect) || f.exception_code || !plan.layout.check.present()) return;
  Collector c{f, plan.layout, arena, {}, {}};
  ModbusPlan& m = plan.modbus;
  plan_function(c, request, with_items, m);
  if (!c.fields.empty()) {
    m.fields = arena.make_array<PlannedField>(c.fields.size());
    std::copy(c.fields.begin(), c.fields.end(), m.fields);
    m.field_count = c.fields.size();
  }
  if (!c.detail.empty()) m.detail = arena.copy(c.detail);
}

}  // namespace pvtap::dissector
