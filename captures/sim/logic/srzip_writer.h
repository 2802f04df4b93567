// Writes logic channels as a sigrok session file (srzip: a zip of `version`, `metadata` and
// the samples in `logic-1-N` chunks), as sigrok-cli and PulseView read it.
#pragma once

#include <string>

#include "logic/logic_signals.h"

namespace pvtap::sim {

// Returns an error text, empty on success. The samples are rendered chunk by chunk as libzip
// asks for them (libzip itself holds about a byte per sample until the archive is closed).
std::string write_srzip(const LogicSignals& signals, const std::string& path);

}  // namespace pvtap::sim
