// MapNodeReader: a map file's TOML values read as the types they must have (private to the core).
#pragma once

#include <toml++/toml.h>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "registers/map_diagnostics.h"
#include "registers/register_map_builder.h"

namespace pvtap::detail {

inline std::uint32_t line_of(const toml::source_region& r) {
  return r.begin.line;
}
inline std::uint32_t column_of(const toml::source_region& r) {
  return r.begin.column;
}

// Every problem of one file goes into one list, in the order the file is read, so that a
// reader of the file sees them as the builder reports them.
class MapNodeReader {
 public:
  explicit MapNodeReader(std::string_view source) { problems_.source = std::string(source); }

  const std::string& source() const { return problems_.source; }
  void fail(const toml::source_region& where, std::string message) {
    problems_.add(line_of(where), column_of(where), std::move(message));
  }
  void fail_at(std::uint32_t line, std::uint32_t column, std::string message) {
    problems_.add(line, column, std::move(message));
  }
  std::vector<MapDiagnostic> take_problems() { return std::move(problems_.items); }

  // The value, or nullptr after a diagnostic that names `what`.
  const toml::value<std::string>* expect_string(const toml::node& node, std::string_view what);
  const toml::value<std::int64_t>* expect_integer(const toml::node& node, std::string_view what);
  // A table whose keys are numbers ("3" or "0x5555") and whose values are texts.
  std::vector<SpecValue> read_number_table(const toml::table& table, std::string_view what);

 private:
  DiagnosticList problems_;
};

}  // namespace pvtap::detail
