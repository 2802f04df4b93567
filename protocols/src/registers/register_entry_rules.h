// The rules one register, coil or discrete-input entry must follow on its own (private to the
// core).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "registers/map_diagnostics.h"
#include "registers/register_map_builder.h"

namespace pvtap::detail {

// Largest run a range entry may describe; keeps the address index small.
inline constexpr std::int64_t kMaxRangeLength = 1024;
// Text entries are decoded into a fixed buffer of this many words.
inline constexpr std::int64_t kMaxTextWords = 16;

// Adds a diagnostic for each rule a field key breaks ([a-z][a-z0-9_]*, at most 64 characters).
void check_key(std::string_view key, std::uint32_t line, std::uint32_t column,
               const std::string& label, DiagnosticList& out);

// "register 'battery_voltage' (0x1006)", for messages about an entry.
std::string entry_label(const RegisterSpec& spec, Dialect dialect);

// Adds a diagnostic for each rule the entry breaks.
void check_register_entry(const RegisterSpec& spec, Dialect dialect, DiagnosticList& out);

// "coil 'pump' (0x0000)", for messages about a coil or discrete-input entry.
std::string coil_label(const CoilSpec& spec, Dialect dialect);

// Adds a diagnostic for each rule a coil or input entry breaks: its key, its name, its address,
// and a dialect whose frames carry no coils (only GSL and plain Modbus maps name them).
void check_coil_entry(const CoilSpec& spec, Dialect dialect, DiagnosticList& out);

}  // namespace pvtap::detail
