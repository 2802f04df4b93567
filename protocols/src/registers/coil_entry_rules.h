// The rules the coil and discrete-input entries of a map follow (private to the core).
#pragma once

#include <string>
#include <vector>

#include "registers/map_diagnostics.h"
#include "registers/register_map_builder.h"

namespace pvtap::detail {

// "coil 'pump' (0x0000)", for messages about an entry.
std::string coil_label(const CoilSpec& spec, Dialect dialect);

// Adds a diagnostic for each rule one entry breaks: its key, its name, its address, and a
// dialect whose frames carry no coils (only GSL and plain Modbus maps name them).
void check_coil_entry(const CoilSpec& spec, Dialect dialect, DiagnosticList& out);

// Entries of one table may not share an address.
void check_coil_addresses(const std::vector<const CoilSpec*>& specs, Dialect dialect,
                          DiagnosticList& out);

}  // namespace pvtap::detail
