// The type of the field the plugin registers for a register map entry: one fact that the fields
// (registration) and the tree description (the value an item shows) share. No Wireshark header.
#pragma once

#include <cstdint>

#include "pvtap/registers/register_map.h"

namespace pvtap::dissector {

enum class RegisterFieldType : std::uint8_t { Uint16, Uint32, Double, String };

inline RegisterFieldType register_field_type(const RegisterDef& def) {
  switch (def.kind) {
    case RegisterKind::Number:
    case RegisterKind::Bcd:
    case RegisterKind::BcdPhaseCapacity:
      return RegisterFieldType::Double;
    case RegisterKind::Raw:
      return def.words > 1 ? RegisterFieldType::Uint32 : RegisterFieldType::Uint16;
    case RegisterKind::Bits:
      return RegisterFieldType::Uint16;
    case RegisterKind::Enum:
    case RegisterKind::DeviceNumber:
      return RegisterFieldType::Uint32;
    case RegisterKind::Text:
    case RegisterKind::BcdYearMonth:
      return RegisterFieldType::String;
  }
  return RegisterFieldType::Uint16;
}

}  // namespace pvtap::dissector
