// The register maps that ship inside the library (embedded from protocols/maps/*.toml).
#include <array>
#include <cstddef>
#include <string>

#include "pvtap/registers/register_map.h"

namespace pvtap::embedded {
extern const unsigned char map_ascii[];
extern const std::size_t map_ascii_size;
extern const unsigned char map_hybrid[];
extern const std::size_t map_hybrid_size;
extern const unsigned char map_gsl[];
extern const std::size_t map_gsl_size;
}  // namespace pvtap::embedded

namespace pvtap {
namespace {

std::string_view as_text(const unsigned char* bytes, std::size_t size) {
  return {reinterpret_cast<const char*>(bytes), size};
}

std::string_view embedded_text(Dialect d) {
  switch (d) {
    case Dialect::Ascii:
      return as_text(embedded::map_ascii, embedded::map_ascii_size);
    case Dialect::Hybrid:
      return as_text(embedded::map_hybrid, embedded::map_hybrid_size);
    case Dialect::Gsl:
      return as_text(embedded::map_gsl, embedded::map_gsl_size);
    case Dialect::Modbus:
      return {};  // plain Modbus devices bring their own map (--map STATION=FILE)
  }
  return {};
}

RegisterMap loaded_or_empty(Dialect d) {
  RegisterMapResult result = load_builtin_register_map(d);
  return result ? result.value() : RegisterMap{};
}

}  // namespace

RegisterMapResult load_builtin_register_map(Dialect d) {
  return load_register_map(embedded_text(d), "builtin:" + std::string(to_string(d)) + ".toml");
}

const RegisterMap& builtin_register_map(Dialect d) {
  // A function-local static is initialized once, even when several threads ask at once.
  static const std::array<RegisterMap, kDialectCount> maps{
      loaded_or_empty(Dialect::Ascii), loaded_or_empty(Dialect::Hybrid),
      loaded_or_empty(Dialect::Gsl), RegisterMap{}};
  return maps[static_cast<std::size_t>(d)];
}

}  // namespace pvtap
