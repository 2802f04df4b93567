// One display-filter field per register map entry, generated from the maps at registration.
#pragma once

#include <epan/ftypes/ftypes.h>

#include <array>

#include "pvtap/registers/register_map.h"

namespace pvtap::dissector {

// RegisterField: the field generated for one map entry (and its flags, for bits registers).
struct RegisterField {
  int hf = -1;
  int ett = -1;                                  // bits registers: the subtree of their flags
  std::array<int, 16> bits = make_unset_bits();  // a boolean field per named flag, else -1
  ftenum type = FT_NONE;

  static constexpr std::array<int, 16> make_unset_bits() {
    std::array<int, 16> ids{};
    ids.fill(-1);
    return ids;
  }
};

// Registers a field for every entry of the dialect's effective map under `proto`, named
// invrtu.hybrid.<key>, invrtu.gsl.<key> or invascii.<key>. Call once per dialect.
void register_register_fields(int proto, Dialect d);

// The field of an entry of the dialect's effective map; null for any other pointer.
const RegisterField* register_field(Dialect d, const RegisterDef* def);

}  // namespace pvtap::dissector
