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

namespace {

// In the order of the Dialect enum (the unit test checks each record's own dialect).
const std::array<const DialectModule*, kDialectCount> kDialects{
    &kAsciiDialect,
    &kHybridDialect,
    &kGslDialect,
    &kModbusDialect,
};

}  // namespace

const DialectModule& dialect_module(Dialect d) {
  return *kDialects[static_cast<std::size_t>(d)];
}

}  // namespace pvtap::detail
