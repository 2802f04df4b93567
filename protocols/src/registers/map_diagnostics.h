// Collects the problems found in one map file (private to the core).
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "pvtap/registers/register_map.h"

namespace pvtap::detail {

// DiagnosticList: problems of one source, each with its line and column.
struct DiagnosticList {
  std::string source;
  std::vector<MapDiagnostic> items;

  void add(std::uint32_t line, std::uint32_t column, std::string message) {
    items.push_back(MapDiagnostic{source, line, column, std::move(message)});
  }
  bool empty() const { return items.empty(); }
};

}  // namespace pvtap::detail
