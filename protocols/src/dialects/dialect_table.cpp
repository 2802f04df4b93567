// The table of dialects: a dialect is its folder under dialects/ and its line in the table here.
#include <array>
#include <cstddef>

#include "dialects/dialect_module.h"

namespace pvtap::detail {

// Each defined in its dialect's folder (dialects/<name>/<name>_dialect.cpp).
extern const DialectModule kAsciiDialect;
extern const DialectModule kHybridDialect;
extern const DialectModule kGslDialect;
extern const DialectModule kModbusDialect;

// In the order of the Dialect enum (the unit test checks each record's own dialect).
const std::array<const DialectModule*, kDialectCount> kDialectTable{
    &kAsciiDialect,
    &kHybridDialect,
    &kGslDialect,
    &kModbusDialect,
};

}  // namespace pvtap::detail

namespace pvtap {

std::string_view dialect_title(Dialect d) {
  return detail::dialect_module(d).title;
}

std::string_view dialect_short_title(Dialect d) {
  return detail::dialect_module(d).short_title;
}

std::string_view check_name(Dialect d) {
  return detail::dialect_module(d).check_name;
}

std::string_view error_reply_name(Dialect d) {
  return detail::dialect_module(d).error_reply_name;
}

bool decimal_register_ids(Dialect d) {
  return detail::dialect_module(d).decimal_register_ids;
}

bool rtu_framed(Dialect d) {
  return detail::dialect_module(d).rtu_framed;
}

unsigned address_step(Dialect d) {
  return detail::dialect_module(d).register_address_step;
}

}  // namespace pvtap
