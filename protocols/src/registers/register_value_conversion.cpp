#include "registers/register_value_conversion.h"

#include <bit>
#include <cmath>

namespace pvtap::detail {
namespace {

// Reads the lowest `digits` BCD digits of `word`; false when one of them is above 9.
bool read_bcd(std::uint32_t word, unsigned digits, std::uint16_t& number) {
  std::uint32_t value = 0;
  for (unsigned i = digits; i-- > 0;) {
    const std::uint32_t digit = (word >> (4 * i)) & 0xFu;
    if (digit > 9) return false;
    value = value * 10 + digit;
  }
  number = static_cast<std::uint16_t>(value);
  return true;
}

void combine(const RegisterDef& def, std::span<const std::uint16_t> words, PairRule option_rule,
             DecodedValue& v) {
  if (words.size() == 1) {
    v.raw = words[0];
    v.signed_raw =
        def.is_signed ? static_cast<std::int16_t>(words[0]) : static_cast<std::int32_t>(v.raw);
    return;
  }
  // Some meters send a pair's low word first (word_order = "low_first").
  const bool low_first = def.word_order == WordOrder::LowFirst;
  const std::uint16_t high = words[low_first ? 1 : 0];
  const std::uint16_t low = words[low_first ? 0 : 1];
  PairRule rule = def.pair_rule == PairRule::FromOptions ? option_rule : def.pair_rule;
  if (rule == PairRule::Decimal) {
    v.raw = std::uint32_t{high} * 10000u + low;
    if (low > 9999) v.add(ValueWarning::LowPartOver9999);
  } else {
    v.raw = (std::uint32_t{high} << 16) | low;
  }
  v.signed_raw = static_cast<std::int32_t>(v.raw);
}

// IEEE-754 single precision: a meter says "no reading" with NaN, so NaN and infinities are
// kept as they are and flagged rather than turned into a number nobody measured.
void convert_float32(const RegisterDef& def, DecodedValue& v) {
  const auto reading = std::bit_cast<float>(v.raw);
  v.value = static_cast<double>(reading) * def.scale;
  if (!std::isfinite(v.value)) v.add(ValueWarning::NotFinite);
}

void convert_enum(const RegisterDef& def, DecodedValue& v) {
  v.enum_text = def.value_text(v.raw);
  if (v.enum_text.empty()) v.add(ValueWarning::UnknownEnumValue);
}

void convert_bits(const RegisterDef& def, DecodedValue& v) {
  for (const BitName bit : SetBits(&def, v.raw)) {
    if (bit.name.empty()) v.add(ValueWarning::UnnamedBitSet);
  }
}

void convert_text(std::span<const std::uint16_t> words, DecodedValue& v) {
  std::uint8_t length = 0;
  for (const std::uint16_t w : words) {
    for (const unsigned shift : {8u, 0u}) {
      const auto c = static_cast<unsigned char>((w >> shift) & 0xFFu);
      const bool printable = c >= 0x20 && c < 0x7F;
      if (!printable && c != 0) v.add(ValueWarning::NonPrintableText);
      v.text_chars[length++] = printable ? static_cast<char>(c) : (c == 0 ? '\0' : '?');
    }
  }
  // Devices pad short names with NULs or spaces.
  while (length > 0 && (v.text_chars[length - 1] == '\0' || v.text_chars[length - 1] == ' ')) {
    --length;
  }
  v.text_length = length;
}

void convert_bcd(const RegisterDef& def, DecodedValue& v) {
  std::uint16_t number = 0;
  if (!read_bcd(v.raw, 4, number)) {
    v.add(ValueWarning::InvalidBcd);
    v.value = 0.0;
    return;
  }
  v.bcd = {number, 0};
  v.value = number * def.scale;
}

void convert_phase_capacity(const RegisterDef& def, DecodedValue& v) {
  std::uint16_t capacity = 0;
  const auto phases = static_cast<std::uint16_t>(v.raw >> 12);
  if (phases > 9 || !read_bcd(v.raw, 3, capacity)) {
    v.add(ValueWarning::InvalidBcd);
    v.value = 0.0;
    return;
  }
  v.bcd = {phases, capacity};
  v.value = capacity * def.scale;
}

void convert_year_month(DecodedValue& v) {
  std::uint16_t year = 0;
  std::uint16_t month = 0;
  if (!read_bcd(v.raw >> 8, 2, year) || !read_bcd(v.raw, 2, month)) {
    v.add(ValueWarning::InvalidBcd);
    v.value = 0.0;
    return;
  }
  v.bcd = {static_cast<std::uint16_t>(2000 + year), month};
  if (month < 1 || month > 12) v.add(ValueWarning::InvalidDate);
  v.value = v.bcd.first * 100.0 + month;
}

}  // namespace

void convert_device_number(const RegisterDef* def, std::span<const std::uint16_t, 2> words,
                           DecodedValue& v) {
  v.raw = (std::uint32_t{words[0]} << 16) | words[1];
  v.signed_raw = static_cast<std::int32_t>(v.raw);
  v.device = DeviceNumber{static_cast<std::uint8_t>(v.raw >> 24), v.raw & 0xFFFFFFu};
  v.value = static_cast<double>(v.device.serial);
  if (def == nullptr) return;
  v.enum_text = def->value_text(v.device.type_code);
  if (v.enum_text.empty()) v.add(ValueWarning::UnknownEnumValue);
}

void convert_words(const RegisterDef& def, std::span<const std::uint16_t> words,
                   PairRule option_rule, DecodedValue& v) {
  if (def.kind == RegisterKind::Text) {
    convert_text(words, v);
    return;
  }
  if (def.kind == RegisterKind::DeviceNumber) {
    convert_device_number(&def, words.first<2>(), v);
    return;
  }
  combine(def, words, def.is_float() ? PairRule::Binary : option_rule, v);
  if (def.has_no_value && v.raw == def.no_value) v.add(ValueWarning::NoValue);
  if (def.is_float()) {
    convert_float32(def, v);
    return;
  }
  v.value =
      (def.is_signed ? static_cast<double>(v.signed_raw) : static_cast<double>(v.raw)) * def.scale;
  switch (def.kind) {
    case RegisterKind::Enum:
      convert_enum(def, v);
      break;
    case RegisterKind::Bits:
      convert_bits(def, v);
      break;
    case RegisterKind::Bcd:
      convert_bcd(def, v);
      break;
    case RegisterKind::BcdPhaseCapacity:
      convert_phase_capacity(def, v);
      break;
    case RegisterKind::BcdYearMonth:
      convert_year_month(v);
      break;
    default:
      break;
  }
}

}  // namespace pvtap::detail
