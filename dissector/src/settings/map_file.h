// Reads a register map file: its text with glib, parsed by the core (which reads no files).
#pragma once

#include <filesystem>

#include "pvtap/registers/register_map.h"

namespace pvtap::dissector {

// The map in `file`, or the loader's problems (file, line and column), or "cannot open".
RegisterMapResult read_map_file(const std::filesystem::path& file);

}  // namespace pvtap::dissector
