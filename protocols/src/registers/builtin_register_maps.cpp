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
  // Each map is parsed the first time it is asked for (a function-local static is initialized
  // once, even when several threads ask at once): an audit of a plain Modbus line parses none.
  switch (d) {
    case Dialect::Ascii: {
      static const RegisterMap ascii = loaded_or_empty(Dialect::Ascii);
      return ascii;
    }
    case Dialect::Hybrid: {
      static const RegisterMap hybrid = loaded_or_empty(Dialect::Hybrid);
      return hybrid;
    }
    case Dialect::Gsl: {
      static const RegisterMap gsl = loaded_or_empty(Dialect::Gsl);
      return gsl;
    }
    case Dialect::Modbus:
      break;
  }
  static const RegisterMap none;
  return none;
}

}  // namespace pvtap
