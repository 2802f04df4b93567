// Reading a register map file: the file's text handed to the core, which reads no files.
#pragma once

#include <string>

#include "pvtap/registers/register_map.h"

namespace pvtap::analyzer {

// The map in the file at `path`, or why not: the core's diagnostics, or "cannot open the
// file" when it cannot be read.
RegisterMapResult read_register_map_file(const std::string& path);

}  // namespace pvtap::analyzer
