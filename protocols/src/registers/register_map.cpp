#include "pvtap/registers/register_map.h"

#include <algorithm>
#include <array>
#include <charconv>

#include "dialects/dialect_module.h"
#include "registers/register_map_data.h"

namespace pvtap {
namespace {

struct KindName {
  RegisterKind kind;
  std::string_view name;
};

constexpr std::array<KindName, 9> kKindNames{{
    {RegisterKind::Number, "number"},
    {RegisterKind::Raw, "raw"},
    {RegisterKind::Enum, "enum"},
    {RegisterKind::Bits, "bits"},
    {RegisterKind::Text, "text"},
    {RegisterKind::Bcd, "bcd"},
    {RegisterKind::BcdPhaseCapacity, "bcd_phase_capacity"},
    {RegisterKind::BcdYearMonth, "bcd_year_month"},
    {RegisterKind::DeviceNumber, "device_number"},
}};

}  // namespace

std::string_view to_string(RegisterKind kind) {
  for (const KindName& k : kKindNames) {
    if (k.kind == kind) return k.name;
  }
  return "?";
}

std::optional<RegisterKind> register_kind_from_string(std::string_view text) {
  for (const KindName& k : kKindNames) {
    if (k.name == text) return k.kind;
  }
  return std::nullopt;
}

std::string_view RegisterDef::value_text(std::uint32_t value) const {
  auto it = std::lower_bound(values.begin(), values.end(), value,
                             [](const EnumText& e, std::uint32_t v) { return e.value < v; });
  return it != values.end() && it->value == value ? it->text : std::string_view{};
}

std::string_view RegisterDef::bit_name(unsigned index) const {
  for (const BitName& b : bits) {
    if (b.index == index) return b.name;
  }
  return {};
}

RegisterAddressText format_register_address(Dialect d, std::uint16_t written_address) {
  if (!detail::dialect_module(d).decimal_register_ids) return format_wire_address(written_address);
  RegisterAddressText out;
  char* first = out.chars.data();
  out.length = static_cast<std::uint8_t>(
      std::to_chars(first, first + out.chars.size(), written_address).ptr - first);
  return out;
}

RegisterAddressText format_wire_address(std::uint16_t wire_address) {
  static constexpr char kDigits[] = "0123456789ABCDEF";
  RegisterAddressText out;
  out.chars[0] = '0';
  out.chars[1] = 'x';
  for (unsigned i = 0; i < 4; ++i) {
    out.chars[2 + i] = kDigits[(static_cast<unsigned>(wire_address) >> (12 - 4 * i)) & 0xFu];
  }
  out.length = 6;
  return out;
}

Dialect RegisterMap::dialect() const {
  return data_ ? data_->dialect : kDefaultDialect;
}
MapMode RegisterMap::mode() const {
  return data_ ? data_->mode : MapMode::Replace;
}
std::string_view RegisterMap::title() const {
  return data_ ? std::string_view(data_->title) : std::string_view{};
}
std::string_view RegisterMap::source_name() const {
  return data_ ? std::string_view(data_->source_name) : std::string_view{};
}
std::span<const RegisterDef> RegisterMap::registers() const {
  return data_ ? std::span<const RegisterDef>(data_->defs) : std::span<const RegisterDef>{};
}

const RegisterDef* RegisterMap::find_key(std::string_view key) const {
  for (const RegisterDef& def : registers()) {
    if (def.key == key) return &def;
  }
  return nullptr;
}

const RegisterDef* RegisterMap::find_address(std::uint16_t address) const {
  const auto defs = registers();
  auto it = std::lower_bound(defs.begin(), defs.end(), address,
                             [](const RegisterDef& d, std::uint16_t a) { return d.address < a; });
  return it != defs.end() && it->address == address ? &*it : nullptr;
}

const RegisterDef* RegisterMap::find_kind(RegisterKind kind) const {
  for (const RegisterDef& def : registers()) {
    if (def.kind == kind) return &def;
  }
  return nullptr;
}

bool RegisterMap::has_scale_factors() const {
  return data_ != nullptr && data_->has_scale_factors;
}

namespace {

const CoilDef* find_point(std::span<const CoilDef> points, std::uint16_t address) {
  auto it = std::lower_bound(points.begin(), points.end(), address,
                             [](const CoilDef& c, std::uint16_t a) { return c.address < a; });
  return it != points.end() && it->address == address ? &*it : nullptr;
}

}  // namespace

std::span<const CoilDef> RegisterMap::coils() const {
  return data_ ? std::span<const CoilDef>(data_->coils) : std::span<const CoilDef>{};
}
std::span<const CoilDef> RegisterMap::discrete_inputs() const {
  return data_ ? std::span<const CoilDef>(data_->discrete_inputs) : std::span<const CoilDef>{};
}
const CoilDef* RegisterMap::find_coil(std::uint16_t address) const {
  return find_point(coils(), address);
}
const CoilDef* RegisterMap::find_discrete_input(std::uint16_t address) const {
  return find_point(discrete_inputs(), address);
}
std::string_view RegisterMap::coil_name(std::uint16_t address) const {
  const CoilDef* def = find_coil(address);
  return def != nullptr ? def->name : std::string_view{};
}
std::string_view RegisterMap::input_name(std::uint16_t address) const {
  const CoilDef* def = find_discrete_input(address);
  return def != nullptr ? def->name : std::string_view{};
}

std::optional<RegisterSlot> RegisterMap::locate(std::uint16_t address) const {
  if (!data_ || address < data_->first_address) return std::nullopt;
  const std::size_t offset = address - data_->first_address;
  if (offset >= data_->slot_by_address.size()) return std::nullopt;
  const std::uint32_t index = data_->slot_by_address[offset];
  if (index == Data::kNoSlot) return std::nullopt;
  const RegisterSlotEntry& entry = data_->slots[index];
  const RegisterDef& def = data_->defs[entry.def_index];
  const unsigned step = data_->step;
  const auto value_address = static_cast<std::uint16_t>(address - entry.word * step);
  return RegisterSlot{&def, entry.word, entry.instance, value_address};
}

std::string MapDiagnostic::to_string() const {
  std::string text = source;
  if (line != 0) {
    text += ':' + std::to_string(line);
    if (column != 0) text += ':' + std::to_string(column);
  }
  text += ": ";
  text += message;
  return text;
}

std::string diagnostic_text(const std::vector<MapDiagnostic>& problems) {
  std::string text;
  for (const MapDiagnostic& d : problems) {
    if (!text.empty()) text += '\n';
    text += d.to_string();
  }
  return text;
}

}  // namespace pvtap
