// Checks register entries and lays them out as a RegisterMap (private to the core).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "pvtap/registers/register_map.h"

namespace pvtap::detail {

// SpecValue: one enum value or bit as read from a file, range not yet checked.
struct SpecValue {
  std::int64_t number = 0;
  std::string text;
  std::uint32_t line = 0;
  std::uint32_t column = 0;
};

// RegisterSpec: one register entry as read from a file, before its rules are checked.
struct RegisterSpec {
  std::int64_t address = 0;
  std::int64_t words = 1;
  std::int64_t repeat = 1;
  RegisterKind kind = RegisterKind::Number;
  bool is_signed = false;
  std::optional<PairRule> pair_rule;    // unset: FromOptions for 2-word entries
  std::optional<WordOrder> word_order;  // unset: high word first
  bool float32 = false;                 // kind = "float32": a number in IEEE-754 words
  std::optional<std::int64_t> decimals;
  double scale = 1.0;
  std::string key;
  std::string name;
  std::string unit;
  std::vector<SpecValue> values;
  std::vector<SpecValue> bits;
  std::string scale_factor;              // key of the entry that scales this one by 10^value
  std::optional<std::int64_t> no_value;  // the raw value that means "no value"
  std::uint32_t line = 0;
  std::uint32_t column = 0;
};

// CoilTable: which table of a map a coil entry belongs to.
enum class CoilTable : std::uint8_t { Coils, DiscreteInputs };

// The table's name in map files: "coil" or "discrete_input".
constexpr std::string_view coil_table_name(CoilTable table) {
  return table == CoilTable::Coils ? "coil" : "discrete_input";
}

// CoilSpec: one [[coil]] or [[discrete_input]] entry as read from a file.
struct CoilSpec {
  CoilTable table = CoilTable::Coils;
  std::int64_t address = 0;
  std::string key;
  std::string name;
  std::uint32_t line = 0;
  std::uint32_t column = 0;
};

// MapHeaderSpec: the file-level settings of a map.
struct MapHeaderSpec {
  Dialect dialect = kDefaultDialect;
  MapMode mode = MapMode::Replace;
  std::string title;
  std::string source_name;
};

// The entry as a spec again, so that maps can be merged through the same checks.
RegisterSpec spec_of(const RegisterDef& def);
CoilSpec spec_of(const CoilDef& def, CoilTable table);

}  // namespace pvtap::detail

namespace pvtap {

// RegisterMapBuilder: validates entries one by one and as a whole, then builds the map.
class RegisterMapBuilder {
 public:
  explicit RegisterMapBuilder(detail::MapHeaderSpec header) : header_(std::move(header)) {}
  void add(detail::RegisterSpec spec) { specs_.push_back(std::move(spec)); }
  void add(detail::CoilSpec spec) { coil_specs_.push_back(std::move(spec)); }
  // A file laid over a SunSpec chain's map may name the chain's scale factors: they are
  // checked when the two are merged, not in the file alone.
  void defer_scale_factors() { defer_scale_factors_ = true; }
  // `earlier` holds problems found while reading the file; they are reported together
  // with the builder's own, sorted by line.
  RegisterMapResult build(std::vector<MapDiagnostic> earlier = {}) &&;

 private:
  detail::MapHeaderSpec header_;
  std::vector<detail::RegisterSpec> specs_;
  std::vector<detail::CoilSpec> coil_specs_;
  bool defer_scale_factors_ = false;
};

}  // namespace pvtap
