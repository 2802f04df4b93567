// The register maps that ship inside the library (embedded from protocols/maps/*.toml).
#include <array>
#include <cstddef>
#include <string>
#include <utility>

#include "dialects/dialect_module.h"
#include "pvtap/registers/register_map.h"

namespace pvtap {
namespace {

// A dialect without a built-in map (plain Modbus: its devices bring their own) has an empty
// one, as does a map that fails to load (the unit tests load each).
RegisterMap loaded_or_empty(Dialect d) {
  if (detail::dialect_module(d).builtin_map_text().empty()) return {};
  RegisterMapResult result = load_builtin_register_map(d);
  return result ? result.value() : RegisterMap{};
}

// Each map is parsed the first time it is asked for (a function-local static is initialized
// once, even when several threads ask at once): an audit of a plain Modbus line parses none.
template <std::size_t I>
const RegisterMap& parsed_once() {
  static const RegisterMap map = loaded_or_empty(static_cast<Dialect>(I));
  return map;
}

template <std::size_t... I>
constexpr auto parsed_maps(std::index_sequence<I...>) {
  return std::array<const RegisterMap& (*)(), sizeof...(I)>{&parsed_once<I>...};
}

}  // namespace

RegisterMapResult load_builtin_register_map(Dialect d) {
  return load_register_map(detail::dialect_module(d).builtin_map_text(),
                           "builtin:" + std::string(to_string(d)) + ".toml");
}

const RegisterMap& builtin_register_map(Dialect d) {
  static constexpr auto maps = parsed_maps(std::make_index_sequence<kDialectCount>{});
  return maps[static_cast<std::size_t>(d)]();
}

}  // namespace pvtap
