#include "report/frame_contents.h"

#include "formatting/json_text.h"
#include "formatting/number_text.h"
#include "pvtap/codec/device_identification.h"
#include "pvtap/codec/function_codes.h"
#include "pvtap/registers/coil_bits.h"

namespace pvtap::analyzer {
namespace {

// Listed in text up to this many; JSON lists every bit that is on.
constexpr std::size_t kBitsShownInText = 16;

bool may_carry_contents(const SessionFrame& f) {
  if (f.frame == nullptr || !f.values_trusted || !modbus_family(f.dialect)) return false;
  switch (f.frame->function) {
    case fc::kReadCoils:
    case fc::kReadDiscreteInputs:
    case fc::kWriteSingleCoil:
    case fc::kWriteMultipleCoils:
    case fc::kDiagnostics:
    case fc::kReportServerId:
    case fc::kEncapsulatedInterface:
      return true;
    default:
      return false;
  }
}

std::size_t bits_on(const CoilBits& bits) {
  std::size_t on = 0;
  for (std::size_t i = 0; i < bits.count; ++i) on += bits.on(i) ? 1u : 0u;
  return on;
}

void append_bits_text(std::string& o, const CoilBits& bits) {
  o += bits.inputs ? "  inputs " : "  coils ";
  if (bits.start) {
    append_uint(o, *bits.start);
    if (bits.count > 1) {
      o += '-';
      append_uint(o, *bits.start + bits.count - 1u);
    }
  } else {
    o += "(start unknown) ";
    append_uint(o, bits.count);
  }
  o += ": ";
  append_uint(o, bits_on(bits));
  o += " on";
  if (bits_on(bits) == 0) return;
  o += " (";
  std::size_t shown = 0;
  for (std::size_t i = 0; i < bits.count; ++i) {
    if (!bits.on(i)) continue;
    if (shown == kBitsShownInText) {
      o += " ...";
      break;
    }
    if (shown++ > 0) o += ' ';
    if (bits.start) {
      append_uint(o, *bits.start + i);
    } else {
      o += '+';
      append_uint(o, i);
    }
  }
  o += ')';
}

// "; pump relay on, valve off": the bits the station's map names.
void append_named_bits_text(std::string& o, const CoilBits& bits, const RegisterMap* map) {
  if (map == nullptr || !bits.start) return;
  bool first = true;
  for (std::size_t i = 0; i < bits.count; ++i) {
    const CoilDef* def = coil_def(*map, bits, i);
    if (def == nullptr) continue;
    o += first ? "; " : ", ";
    first = false;
    o += def->name;
    o += bits.on(i) ? " on" : " off";
  }
}

// ,"named":[{"address":19,"key":"pump","name":"pump relay","on":true}]
void append_named_bits_json(std::string& o, const CoilBits& bits, const RegisterMap* map) {
  if (map == nullptr || !bits.start) return;
  bool first = true;
  for (std::size_t i = 0; i < bits.count; ++i) {
    const CoilDef* def = coil_def(*map, bits, i);
    if (def == nullptr) continue;
    o += first ? ",\"named\":[" : ",";
    first = false;
    o += "{\"address\":";
    append_uint(o, def->address);
    o += ",\"key\":";
    append_json_string(o, def->key);
    o += ",\"name\":";
    append_json_string(o, def->name);
    o += bits.on(i) ? ",\"on\":true}" : ",\"on\":false}";
  }
  if (!first) o += ']';
}

void append_bits_json(std::string& o, const CoilBits& bits, const RegisterMap* map) {
  o += bits.inputs ? ",\"inputs\":{\"start\":" : ",\"coils\":{\"start\":";
  if (bits.start) {
    append_uint(o, *bits.start);
  } else {
    o += "null";
  }
  o += ",\"count\":";
  append_uint(o, bits.count);
  o += ",\"on\":[";
  bool first = true;
  for (std::size_t i = 0; i < bits.count; ++i) {
    if (!bits.on(i)) continue;
    if (!first) o += ',';
    first = false;
    // Without the request the bits are numbered from 0.
    append_uint(o, bits.start.value_or(0) + i);
  }
  o += ']';
  append_named_bits_json(o, bits, map);
  o += '}';
}

void append_device_text(std::string& o, const DeviceIdentification& id) {
  o += "  device:";
  for (std::size_t i = 0; i < id.object_count; ++i) {
    o += i == 0 ? " " : ", ";
    o += device_object_name(id.objects[i].id);
    o += " \"";
    o += id.objects[i].value;
    o += '"';
  }
  if (id.more_follows) o += " (more follows)";
}

void append_device_json(std::string& o, const DeviceIdentification& id) {
  o += ",\"device\":{\"conformity\":";
  append_uint(o, id.conformity);
  o += ",\"more_follows\":";
  o += id.more_follows ? "true" : "false";
  o += ",\"objects\":[";
  for (std::size_t i = 0; i < id.object_count; ++i) {
    if (i > 0) o += ',';
    o += "{\"id\":";
    append_uint(o, id.objects[i].id);
    o += ",\"name\":";
    append_json_string(o, device_object_name(id.objects[i].id));
    o += ",\"value\":";
    append_json_string(o, id.objects[i].value);
    o += '}';
  }
  o += "]}";
}

}  // namespace

void append_contents_text(std::string& o, const SessionFrame& f) {
  if (!may_carry_contents(f)) return;
  const Frame& frame = *f.frame;
  if (const auto bits = coil_bits(frame, f.placing_request)) {
    append_bits_text(o, *bits);
    append_named_bits_text(o, *bits, f.map);
  }
  if (frame.sub_function) {
    o += "  diagnostics: ";
    const std::string_view name = fc::diagnostics_name(*frame.sub_function);
    if (name.empty()) {
      o += "sub-function ";
      append_uint(o, *frame.sub_function);
    } else {
      o += name;
    }
  }
  if (const auto id = read_device_identification(frame)) append_device_text(o, *id);
  if (const auto server = read_server_id(frame)) {
    o += "  server ID";
    if (!server->text.empty()) {
      o += " \"";
      o += server->text;
      o += '"';
    }
    if (server->running) o += *server->running ? " (running)" : " (not running)";
  }
}

void append_contents_json(std::string& o, const SessionFrame& f) {
  if (!may_carry_contents(f)) return;
  const Frame& frame = *f.frame;
  if (const auto bits = coil_bits(frame, f.placing_request)) append_bits_json(o, *bits, f.map);
  if (frame.sub_function) {
    o += ",\"diagnostics\":{\"sub_function\":";
    append_uint(o, *frame.sub_function);
    o += ",\"name\":";
    const std::string_view name = fc::diagnostics_name(*frame.sub_function);
    if (name.empty()) {
      o += "null";
    } else {
      append_json_string(o, name);
    }
    o += '}';
  }
  if (const auto id = read_device_identification(frame)) append_device_json(o, *id);
  if (const auto server = read_server_id(frame)) {
    o += ",\"server_id\":{\"text\":";
    append_json_string(o, server->text);
    o += ",\"running\":";
    o += !server->running ? "null" : *server->running ? "true" : "false";
    o += '}';
  }
}

}  // namespace pvtap::analyzer
