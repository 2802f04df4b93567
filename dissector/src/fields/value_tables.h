// Value strings for fields whose values have names, built once from the core's tables.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "wireshark_api/value_string.h"

#include "pvtap/codec/dialect.h"
#include "pvtap/registers/register_map.h"

namespace pvtap::dissector {

// A value_string table of `entries` that lives as long as Wireshark.
const value_string* persist_value_strings(
    const std::vector<std::pair<std::uint32_t, std::string>>& entries);

const value_string* dialect_names();
const value_string* role_names();
// Function codes of the given dialects ("read running data"), GSL exceptions included.
const value_string* function_names(DialectSet dialects);
// GSL exception codes ("address (ID) out of range").
const value_string* exception_names();
// The texts of an enum register, or of a device number's type codes; null when it has none.
const value_string* register_value_names(const RegisterDef& def);

}  // namespace pvtap::dissector
