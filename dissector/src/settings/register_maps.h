// The register map in effect for each dialect: the built-in one, or what the user's map files
// in the pvtap/ folder of the Wireshark personal configuration folder make of it.
#pragma once

#include "pvtap/registers/register_map.h"

namespace pvtap::dissector {

// Loads the user's map files once, at protocol registration, in file-name order; a broken
// file is reported through Wireshark's failure reporting and skipped.
void load_register_maps();

const RegisterMap& effective_map(Dialect d);

}  // namespace pvtap::dissector
