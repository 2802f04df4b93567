#include "registers/coil_entry_rules.h"

#include <map>
#include <utility>

#include "registers/coil_entry_reader.h"
#include "registers/register_entry_rules.h"

namespace pvtap::detail {

std::string coil_label(const CoilSpec& spec, Dialect dialect) {
  std::string label(coil_table_name(spec.table));
  if (!spec.key.empty()) label += " '" + spec.key + "'";
  if (spec.address >= 0 && spec.address <= 0xFFFF) {
    label += " (";
    label += format_register_address(dialect, static_cast<std::uint16_t>(spec.address)).view();
    label += ")";
  }
  return label;
}

void check_coil_entry(const CoilSpec& spec, Dialect dialect, DiagnosticList& out) {
  const std::string label = coil_label(spec, dialect);
  if (!modbus_family(dialect)) {
    out.add(spec.line, spec.column,
            label + ": only gsl and modbus maps name coils and discrete inputs");
  }
  check_key(spec.key, spec.line, spec.column, label, out);
  if (spec.name.empty()) out.add(spec.line, spec.column, label + ": name is missing or empty");
  if (spec.address < 0 || spec.address > 0xFFFF) {
    out.add(spec.line, spec.column, label + ": address must be 0 .. 65535");
  }
}

void check_coil_addresses(const std::vector<const CoilSpec*>& specs, Dialect dialect,
                          DiagnosticList& out) {
  std::map<std::pair<CoilTable, std::int64_t>, const CoilSpec*> first_use;
  for (const CoilSpec* spec : specs) {
    auto [it, inserted] = first_use.emplace(std::pair{spec->table, spec->address}, spec);
    if (!inserted) {
      out.add(spec->line, spec->column,
              coil_label(*spec, dialect) + ": duplicate address, also defined at line " +
                  std::to_string(it->second->line));
    }
  }
}

}  // namespace pvtap::detail
