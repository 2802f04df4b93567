// The rules one register entry must follow on its own (private to the core).
#pragma once

#include <string>

#include "registers/map_diagnostics.h"
#include "registers/register_map_builder.h"

namespace pvtap::detail {

// Largest run a range entry may describe; keeps the address index small.
inline constexpr std::int64_t kMaxRangeLength = 1024;
// Text entries are decoded into a fixed buffer of this many words.
inline constexpr std::int64_t kMaxTextWords = 16;

// "register 'battery_voltage' (0x1006)", for messages about an entry.
std::string entry_label(const RegisterSpec& spec, Dialect dialect);

// Adds a diagnostic for each rule the entry breaks.
void check_register_entry(const RegisterSpec& spec, Dialect dialect, DiagnosticList& out);

}  // namespace pvtap::detail
