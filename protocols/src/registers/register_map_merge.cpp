// Laying a user's map over the built-in one.
#include <algorithm>
#include <set>
#include <string>

#include "pvtap/registers/register_map.h"
#include "registers/register_map_builder.h"

namespace pvtap {
namespace {

// The addresses an entry covers, kept apart for singles and ranges: a single inside a range
// is a carve-out, not a conflict, so only like entries replace each other by address.
struct CoveredAddresses {
  std::set<std::uint16_t> singles;
  std::set<std::uint16_t> ranges;
  std::set<std::string_view> keys;

  void add(const RegisterDef& def, unsigned step) {
    auto& into = def.is_range() ? ranges : singles;
    const unsigned slots = static_cast<unsigned>(def.words) * def.repeat;
    for (unsigned k = 0; k < slots; ++k)
      into.insert(static_cast<std::uint16_t>(def.address + k * step));
    keys.insert(def.key);
  }

  bool conflicts_with(const RegisterDef& def, unsigned step) const {
    if (keys.contains(def.key)) return true;
    const auto& against = def.is_range() ? ranges : singles;
    const unsigned slots = static_cast<unsigned>(def.words) * def.repeat;
    for (unsigned k = 0; k < slots; ++k) {
      if (against.contains(static_cast<std::uint16_t>(def.address + k * step))) return true;
    }
    return false;
  }
};

// An overlay's coil replaces the base's coil at its address or with its key; so for inputs.
void add_coils(const RegisterMap& base, const RegisterMap& overlay, RegisterMapBuilder& builder) {
  using detail::CoilTable;
  for (const CoilTable table : {CoilTable::Coils, CoilTable::DiscreteInputs}) {
    const auto points = [&](const RegisterMap& m) {
      return table == CoilTable::Coils ? m.coils() : m.discrete_inputs();
    };
    for (const CoilDef& def : points(base)) {
      const bool replaced = std::any_of(
          points(overlay).begin(), points(overlay).end(),
          [&](const CoilDef& o) { return o.address == def.address || o.key == def.key; });
      if (!replaced) builder.add(detail::spec_of(def, table));
    }
    for (const CoilDef& def : points(overlay)) builder.add(detail::spec_of(def, table));
  }
}

}  // namespace

RegisterMapResult merge_register_maps(const RegisterMap& base, const RegisterMap& overlay) {
  if (base.dialect() != overlay.dialect()) {
    MapDiagnostic d{std::string(overlay.source_name()), 0, 0,
                    "a " + std::string(to_string(overlay.dialect())) + " map cannot extend a " +
                        std::string(to_string(base.dialect())) + " map"};
    return RegisterMapResult::failure({std::move(d)});
  }
  const unsigned step = address_step(base.dialect());
  CoveredAddresses replaced;
  for (const RegisterDef& def : overlay.registers()) replaced.add(def, step);

  detail::MapHeaderSpec header;
  header.dialect = base.dialect();
  header.mode = MapMode::Replace;  // the result is complete in itself
  header.title = std::string(overlay.title().empty() ? base.title() : overlay.title());
  header.source_name = std::string(base.source_name()) + " + " + std::string(overlay.source_name());
  RegisterMapBuilder builder(std::move(header));
  for (const RegisterDef& def : base.registers()) {
    if (!replaced.conflicts_with(def, step)) builder.add(detail::spec_of(def));
  }
  for (const RegisterDef& def : overlay.registers()) builder.add(detail::spec_of(def));
  add_coils(base, overlay, builder);
  return std::move(builder).build();
}

RegisterMapResult resolve_user_register_map(const RegisterMap& user) {
  if (user.mode() == MapMode::Replace) return user;
  return merge_register_maps(builtin_register_map(user.dialect()), user);
}

RegisterMapResult stack_register_map(const RegisterMap& in_effect, const RegisterMap& user) {
  if (user.mode() == MapMode::Replace) return user;
  return merge_register_maps(in_effect, user);
}

}  // namespace pvtap
