// The table of the simulator's inverter dialects: a dialect is its file here and its line below.
#include <array>

#include "dialects/inverter_dialect.h"

namespace pvtap::sim {

extern const InverterDialect kAsciiInverter;
extern const InverterDialect kHybridInverter;
extern const InverterDialect kGslInverter;

namespace {

constexpr std::array<const InverterDialect*, 3> kInverterDialects{&kAsciiInverter, &kHybridInverter,
                                                                  &kGslInverter};

}  // namespace

const InverterDialect* inverter_dialect(Dialect d) {
  for (const InverterDialect* r : kInverterDialects) {
    if (r->dialect == d) return r;
  }
  return nullptr;
}

}  // namespace pvtap::sim
