#include "registers/register_entry_rules.h"

#include <algorithm>
#include <cmath>
#include <set>

namespace pvtap::detail {
namespace {

// What each kind allows; one row per kind, in the order of RegisterKind.
struct KindRules {
  std::int64_t min_words;
  std::int64_t max_words;
  bool takes_values;
  bool takes_bits;
  bool takes_sign;
  bool takes_range;
};

// A float32 is a number read from IEEE-754 words: exactly two of them, its own sign.
constexpr KindRules kFloat32Rules{2, 2, false, false, false, false};

KindRules rules_of(RegisterKind kind) {
  switch (kind) {
    case RegisterKind::Number:
      return {1, 2, false, false, true, true};
    case RegisterKind::Raw:
      return {1, 2, false, false, false, true};
    case RegisterKind::Enum:
      return {1, 2, true, false, false, false};
    case RegisterKind::Bits:
      return {1, 1, false, true, false, false};
    case RegisterKind::Text:
      return {1, kMaxTextWords, false, false, false, false};
    case RegisterKind::Bcd:
    case RegisterKind::BcdPhaseCapacity:
    case RegisterKind::BcdYearMonth:
      return {1, 1, false, false, false, false};
    case RegisterKind::DeviceNumber:
      return {2, 2, true, false, false, false};
  }
  return {1, 1, false, false, false, false};
}

bool is_key_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
}

KindRules rules_of(const RegisterSpec& spec) {
  return spec.float32 ? kFloat32Rules : rules_of(spec.kind);
}

std::string kind_name(const RegisterSpec& spec) {
  return spec.float32 ? "float32" : std::string(to_string(spec.kind));
}

// Kinds whose two words make one number, so that their order on the wire is a question.
bool takes_word_order(const RegisterSpec& spec) {
  return spec.words == 2 && (spec.kind == RegisterKind::Number || spec.kind == RegisterKind::Raw ||
                             spec.kind == RegisterKind::Enum);
}

void check_width(const RegisterSpec& spec, const std::string& label, Dialect dialect,
                 DiagnosticList& out) {
  const KindRules rules = rules_of(spec);
  const std::string kind = kind_name(spec);
  if (spec.words < rules.min_words || spec.words > rules.max_words) {
    out.add(
        spec.line, spec.column,
        label + ": a " + kind + " register is " + std::to_string(rules.min_words) +
            (rules.max_words > rules.min_words ? " to " + std::to_string(rules.max_words) : "") +
            " word(s) wide, not " + std::to_string(spec.words));
    return;
  }
  if (spec.repeat > 1 && (!rules.takes_range || spec.words != 1)) {
    out.add(spec.line, spec.column,
            label + ": only one-word number or raw registers can be a range ('last')");
  }
  if (spec.repeat > kMaxRangeLength) {
    out.add(spec.line, spec.column,
            label + ": a range may hold at most " + std::to_string(kMaxRangeLength) + " registers");
  }
  if (spec.address < 0 || spec.address > 0xFFFF) {
    out.add(spec.line, spec.column, label + ": address must be 0 .. 65535");
    return;
  }
  const std::int64_t step = address_step(dialect);
  const std::int64_t last = spec.address + (spec.words * spec.repeat - 1) * step;
  if (last > 0xFFFF) {
    out.add(spec.line, spec.column, label + ": its words run past address 65535");
  }
}

void check_number_settings(const RegisterSpec& spec, const std::string& label,
                           DiagnosticList& out) {
  if (!std::isfinite(spec.scale) || spec.scale <= 0.0) {
    out.add(spec.line, spec.column, label + ": scale must be a positive number");
  }
  if (spec.decimals && (*spec.decimals < 0 || *spec.decimals > 9)) {
    out.add(spec.line, spec.column, label + ": decimals must be 0 .. 9");
  }
  if (spec.pair_rule && spec.words != 2) {
    out.add(spec.line, spec.column, label + ": 'combine' applies only to 2-word registers");
  }
  if (spec.pair_rule && spec.float32) {
    out.add(spec.line, spec.column, label + ": 'combine' does not apply to a float32 register");
  }
  if (spec.word_order && !takes_word_order(spec)) {
    out.add(spec.line, spec.column,
            label + ": 'word_order' applies only to 2-word number, float32, raw or enum registers");
  }
  if (spec.is_signed && spec.float32) {
    out.add(spec.line, spec.column, label + ": a float32 register carries its own sign");
  } else if (spec.is_signed && !rules_of(spec.kind).takes_sign) {
    out.add(spec.line, spec.column, label + ": only number registers can be signed");
  }
  if (spec.is_signed && spec.pair_rule == PairRule::Decimal) {
    out.add(spec.line, spec.column, label + ": a decimal pair cannot be signed");
  }
}

std::int64_t largest_value(const RegisterSpec& spec) {
  if (spec.kind == RegisterKind::DeviceNumber) return 0xFF;  // the values name the type code
  return spec.words >= 2 ? 0xFFFFFFFFll : 0xFFFFll;
}

void check_values(const RegisterSpec& spec, const std::string& label, DiagnosticList& out) {
  const bool allowed = rules_of(spec.kind).takes_values;
  if (!allowed && !spec.values.empty()) {
    out.add(spec.line, spec.column, label + ": 'values' needs kind enum or device_number");
    return;
  }
  if (spec.kind == RegisterKind::Enum && spec.values.empty()) {
    out.add(spec.line, spec.column, label + ": an enum register needs 'values'");
  }
  const std::int64_t largest = largest_value(spec);
  std::set<std::int64_t> seen;
  for (const SpecValue& v : spec.values) {
    if (v.number < 0 || v.number > largest) {
      out.add(v.line, v.column,
              label + ": value " + std::to_string(v.number) + " does not fit (0 .. " +
                  std::to_string(largest) + ")");
    }
    if (!seen.insert(v.number).second) {
      out.add(v.line, v.column, label + ": value " + std::to_string(v.number) + " is listed twice");
    }
    if (v.text.empty()) out.add(v.line, v.column, label + ": a value's text is empty");
  }
}

void check_bits(const RegisterSpec& spec, const std::string& label, DiagnosticList& out) {
  if (spec.kind != RegisterKind::Bits) {
    if (!spec.bits.empty()) out.add(spec.line, spec.column, label + ": 'bits' needs kind bits");
    return;
  }
  if (spec.bits.empty()) out.add(spec.line, spec.column, label + ": a bits register needs 'bits'");
  std::set<std::int64_t> seen;
  for (const SpecValue& b : spec.bits) {
    if (b.number < 0 || b.number > 15) {
      out.add(b.line, b.column,
              label + ": bit " + std::to_string(b.number) + " is out of range 0 .. 15");
    }
    if (!seen.insert(b.number).second) {
      out.add(b.line, b.column, label + ": bit " + std::to_string(b.number) + " is named twice");
    }
    if (b.text.empty()) out.add(b.line, b.column, label + ": a bit's name is empty");
  }
}

// A scale factor scales a number; a "no value" mark must be a raw value the entry can hold.
void check_device_marks(const RegisterSpec& spec, const std::string& label, DiagnosticList& out) {
  if (!spec.scale_factor.empty() && (spec.kind != RegisterKind::Number || spec.float32)) {
    out.add(spec.line, spec.column, label + ": only integer number registers take a scale_factor");
  }
  if (!spec.no_value) return;
  const std::int64_t largest = spec.words >= 2 ? 0xFFFFFFFFLL : 0xFFFFLL;
  if (*spec.no_value < 0 || *spec.no_value > largest) {
    out.add(spec.line, spec.column,
            label + ": no_value must be a raw value of the register's " +
                std::to_string(spec.words) + " word(s), 0 .. " + std::to_string(largest));
  }
}

}  // namespace

void check_key(std::string_view key, std::uint32_t line, std::uint32_t column,
               const std::string& label, DiagnosticList& out) {
  if (key.empty()) {
    out.add(line, column, label + ": key is missing or empty");
    return;
  }
  if (key.size() > 64) out.add(line, column, label + ": key is longer than 64 characters");
  if (key.front() < 'a' || key.front() > 'z') {
    out.add(line, column, label + ": key must start with a lowercase letter");
  }
  if (!std::all_of(key.begin(), key.end(), is_key_char)) {
    out.add(line, column,
            label + ": key may hold only lowercase letters, digits and '_' (it names a field)");
  }
}

std::string entry_label(const RegisterSpec& spec, Dialect dialect) {
  std::string label = "register";
  if (!spec.key.empty()) label += " '" + spec.key + "'";
  if (spec.address >= 0 && spec.address <= 0xFFFF) {
    label += " (";
    label += format_register_address(dialect, static_cast<std::uint16_t>(spec.address)).view();
    label += ")";
  }
  return label;
}

void check_register_entry(const RegisterSpec& spec, Dialect dialect, DiagnosticList& out) {
  const std::string label = entry_label(spec, dialect);
  check_key(spec.key, spec.line, spec.column, label, out);
  if (spec.name.empty()) out.add(spec.line, spec.column, label + ": name is missing or empty");
  check_width(spec, label, dialect, out);
  check_number_settings(spec, label, out);
  check_values(spec, label, out);
  check_bits(spec, label, out);
  check_device_marks(spec, label, out);
}

std::string coil_label(const CoilSpec& spec, Dialect dialect) {
  std::string label(coil_table_name(spec.table));
  if (!spec.key.empty()) label += " '" + spec.key + "'";
  if (spec.address >= 0 && spec.address <= 0xFFFF) {
    label += " (";
    label += format_register_address(dialect, static_cast<std::uint16_t>(spec.address)).view();
    label += ")";
  }
  return label;
}

void check_coil_entry(const CoilSpec& spec, Dialect dialect, DiagnosticList& out) {
  const std::string label = coil_label(spec, dialect);
  if (!modbus_family(dialect)) {
    out.add(spec.line, spec.column,
            label + ": only gsl and modbus maps name coils and discrete inputs");
  }
  check_key(spec.key, spec.line, spec.column, label, out);
  if (spec.name.empty()) out.add(spec.line, spec.column, label + ": name is missing or empty");
  if (spec.address < 0 || spec.address > 0xFFFF) {
    out.add(spec.line, spec.column, label + ": address must be 0 .. 65535");
  }
}

}  // namespace pvtap::detail
