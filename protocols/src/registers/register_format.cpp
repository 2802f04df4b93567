#include "pvtap/registers/register_format.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>

namespace pvtap {
namespace {

using FixedChars = std::array<char, 64>;

// `value` with `decimals` digits after the point; returns the end of the text in `buf`.
char* write_fixed(FixedChars& buf, double value, unsigned decimals) {
  return std::to_chars(buf.data(), buf.data() + buf.size(), value, std::chars_format::fixed,
                       static_cast<int>(decimals))
      .ptr;
}

void append_fixed(std::string& out, double value, unsigned decimals) {
  FixedChars buf{};
  out.append(buf.data(), write_fixed(buf, value, decimals));
}

void append_hex(std::string& out, std::uint32_t value, unsigned digits) {
  static constexpr char kDigits[] = "0123456789ABCDEF";
  out += "0x";
  for (unsigned i = digits; i-- > 0;) out += kDigits[(value >> (4 * i)) & 0xFu];
}

void append_unit(std::string& out, std::string_view unit) {
  if (unit.empty()) return;
  out += ' ';
  out += unit;
}

// A float32 NaN is a device saying it has no reading: its words are shown, not a number.
void append_not_finite(std::string& out, const DecodedValue& v) {
  if (std::isnan(v.value)) {
    out += "not a number (";
    append_hex(out, v.raw, 8);
    out += ')';
    return;
  }
  out += v.value < 0 ? "-infinity" : "infinity";
  append_unit(out, v.def->unit);
}

void append_number(std::string& out, const DecodedValue& v) {
  if (!std::isfinite(v.value)) {
    append_not_finite(out, v);
    return;
  }
  append_fixed(out, v.value, shown_decimals(v));
  append_unit(out, v.def->unit);
}

void append_bits(std::string& out, const DecodedValue& v) {
  bool any = false;
  for (const BitName bit : v.set_bits()) {
    if (any) out += ", ";
    any = true;
    if (bit.name.empty()) {
      out += "bit " + std::to_string(bit.index);
    } else {
      out += bit.name;
    }
  }
  if (!any) out += "none";
}

void append_phase_capacity(std::string& out, const DecodedValue& v) {
  switch (v.bcd.first) {
    case 1:
      out += "single phase";
      break;
    case 3:
      out += "three phase";
      break;
    default:
      out += std::to_string(v.bcd.first) + " phases";
      break;
  }
  out += ", ";
  append_number(out, v);
}

void append_year_month(std::string& out, const DecodedValue& v) {
  out += std::to_string(v.bcd.first);
  out += v.bcd.second < 10 ? "-0" : "-";
  out += std::to_string(v.bcd.second);
}

void append_device_number(std::string& out, const DecodedValue& v) {
  static constexpr char kDigits[] = "0123456789ABCDEF";
  out += kDigits[v.device.type_code >> 4];
  out += kDigits[v.device.type_code & 0xFu];
  out += ' ';
  out += v.enum_text.empty() ? std::string_view("unknown device type") : v.enum_text;
  out += ", serial " + std::to_string(v.device.serial);
}

void append_enum(std::string& out, const DecodedValue& v) {
  if (v.enum_text.empty()) {
    out += "unknown value " + std::to_string(v.raw);
  } else {
    out += v.enum_text;
  }
}

void append_complete_value(std::string& out, const DecodedValue& v) {
  const RegisterDef& def = *v.def;
  const bool bad_bcd = v.has(ValueWarning::InvalidBcd);
  switch (def.kind) {
    case RegisterKind::Number:
      append_number(out, v);
      return;
    case RegisterKind::Raw:
      append_hex(out, v.raw, 4u * def.words);
      return;
    case RegisterKind::Enum:
      append_enum(out, v);
      return;
    case RegisterKind::Bits:
      append_bits(out, v);
      return;
    case RegisterKind::Text:
      out += v.text();
      return;
    case RegisterKind::DeviceNumber:
      append_device_number(out, v);
      return;
    case RegisterKind::Bcd:
    case RegisterKind::BcdPhaseCapacity:
    case RegisterKind::BcdYearMonth:
      break;
  }
  if (bad_bcd) {
    out += "invalid BCD ";
    append_hex(out, v.raw, 4);
  } else if (def.kind == RegisterKind::Bcd) {
    append_number(out, v);
  } else if (def.kind == RegisterKind::BcdPhaseCapacity) {
    append_phase_capacity(out, v);
  } else {
    append_year_month(out, v);
  }
}

}  // namespace

void append_value_text(std::string& out, const DecodedValue& v) {
  if (v.def == nullptr) {
    append_hex(out, v.raw, 4);
  } else if (!v.complete()) {
    out += "incomplete (" + std::to_string(v.words_present) + " of " +
           std::to_string(v.def->words) + " words in the frame)";
  } else if (v.has(ValueWarning::NoValue)) {
    out += "no value (";
    append_hex(out, v.raw, 4u * v.def->words);
    out += ')';
  } else {
    append_complete_value(out, v);
  }
}

unsigned shown_decimals(const DecodedValue& v) {
  return std::max<unsigned>(v.def->decimals, v.scale_decimals);
}

double value_as_shown(const DecodedValue& v) {
  if (v.def == nullptr || !std::isfinite(v.value)) return v.value;
  FixedChars buf{};
  double shown = v.value;
  std::from_chars(buf.data(), write_fixed(buf, v.value, shown_decimals(v)), shown);
  return shown;
}

std::string format_value(const DecodedValue& v) {
  std::string out;
  append_value_text(out, v);
  return out;
}

RegisterAddressText format_value_address(const DecodedValue& v, Dialect d) {
  const bool hex_wire = v.has(ValueWarning::NoWrittenAddress);
  return hex_wire ? format_wire_address(v.address) : format_register_address(d, v.address);
}

std::string_view describe(ValueWarning w) {
  switch (w) {
    case ValueWarning::NotInMap:
      return "no register map entry covers this word";
    case ValueWarning::Incomplete:
      return "part of this multi-word value is not in the frame";
    case ValueWarning::LowPartOver9999:
      return "low part above 9999 in a decimal (x10000) pair";
    case ValueWarning::UnknownEnumValue:
      return "value not listed in the register map";
    case ValueWarning::UnnamedBitSet:
      return "a set bit has no name in the register map";
    case ValueWarning::InvalidBcd:
      return "BCD digit above 9";
    case ValueWarning::InvalidDate:
      return "month outside 1..12";
    case ValueWarning::NonPrintableText:
      return "text holds non-printable characters";
    case ValueWarning::NoWrittenAddress:
      return "wire address has no decimal ID reading";
    case ValueWarning::NotFinite:
      return "float32 value is not a number or infinite";
    case ValueWarning::NoValue:
      return "the device's mark for no value";
    case ValueWarning::NoScaleFactor:
      return "its scale factor register was not read: shown without it";
  }
  return "?";
}

}  // namespace pvtap
