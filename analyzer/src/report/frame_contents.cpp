#include "report/frame_contents.h"

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

// "named":[{"address":19,"key":"pump","name":"pump relay","on":true}]
void write_named_bits(JsonWriter& w, const CoilBits& bits, const RegisterMap* map) {
  if (map == nullptr || !bits.start) return;
  bool first = true;
  for (std::size_t i = 0; i < bits.count; ++i) {
    const CoilDef* def = coil_def(*map, bits, i);
    if (def == nullptr) continue;
    if (first) {
      w.key("named");
      w.begin_array();
      first = false;
    }
    w.begin_object();
    w.field("address", def->address);
    w.field("key", def->key);
    w.field("name", def->name);
    w.field_bool("on", bits.on(i));
    w.end_object();
  }
  if (!first) w.end_array();
}

void write_bits(JsonWriter& w, const CoilBits& bits, const RegisterMap* map) {
  if (bits.inputs) {
    w.key("inputs");
  } else {
    w.key("coils");
  }
  w.begin_object();
  w.key("start");
  if (bits.start) {
    w.uint(*bits.start);
  } else {
    w.null();
  }
  w.field("count", bits.count);
  w.key("on");
  w.begin_array();
  for (std::size_t i = 0; i < bits.count; ++i) {
    // Without the request the bits are numbered from 0.
    if (bits.on(i)) w.uint(bits.start.value_or(0) + i);
  }
  w.end_array();
  write_named_bits(w, bits, map);
  w.end_object();
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

void write_device(JsonWriter& w, const DeviceIdentification& id) {
  w.key("device");
  w.begin_object();
  w.field("conformity", id.conformity);
  w.field_bool("more_follows", id.more_follows);
  w.key("objects");
  w.begin_array();
  for (std::size_t i = 0; i < id.object_count; ++i) {
    w.begin_object();
    w.field("id", id.objects[i].id);
    w.field("name", device_object_name(id.objects[i].id));
    w.field("value", id.objects[i].value);
    w.end_object();
  }
  w.end_array();
  w.end_object();
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

void write_contents_json(JsonWriter& w, const SessionFrame& f) {
  if (!may_carry_contents(f)) return;
  const Frame& frame = *f.frame;
  if (const auto bits = coil_bits(frame, f.placing_request)) write_bits(w, *bits, f.map);
  if (frame.sub_function) {
    w.key("diagnostics");
    w.begin_object();
    w.field("sub_function", *frame.sub_function);
    w.key("name");
    const std::string_view name = fc::diagnostics_name(*frame.sub_function);
    if (name.empty()) {
      w.null();
    } else {
      w.string(name);
    }
    w.end_object();
  }
  if (const auto id = read_device_identification(frame)) write_device(w, *id);
  if (const auto server = read_server_id(frame)) {
    w.key("server_id");
    w.begin_object();
    w.field("text", server->text);
    w.key("running");
    if (server->running) {
      w.boolean(*server->running);
    } else {
      w.null();
    }
    w.end_object();
  }
}

}  // namespace pvtap::analyzer
