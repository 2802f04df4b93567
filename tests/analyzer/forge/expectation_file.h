// Writes what a generated capture must audit to, as JSON for tests/analyzer/check_audit.py.
#pragma once

#include <string>

#include "bus_plan.h"

namespace pvtap::forge {

// {"args":[...],"counts":{...},"frames":[["<hex>","request","ok"],...],"values":[...]}
void write_expectation(const std::string& path, const Expected& e);

}  // namespace pvtap::forge
