#include "registers/register_map_builder.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "registers/map_diagnostics.h"
#include "registers/register_entry_rules.h"
#include "registers/register_map_data.h"

namespace pvtap {
namespace {

using detail::CoilSpec;
using detail::RegisterSpec;

std::uint16_t to_u16(std::int64_t v) {
  return static_cast<std::uint16_t>(v);
}

// Every address an entry covers, first word first.
template <typename Visit>
void for_each_covered_address(const RegisterSpec& spec, Dialect dialect, Visit visit) {
  const std::int64_t step = address_step(dialect);
  const std::int64_t slots = spec.words * spec.repeat;
  for (std::int64_t k = 0; k < slots; ++k) {
    visit(to_u16(spec.address + k * step), to_u16(k / spec.words), to_u16(k % spec.words));
  }
}

// Keys name fields, so a coil's key may not be a register's either.
void check_keys_unique(const std::vector<const RegisterSpec*>& specs,
                       const std::vector<const CoilSpec*>& coils, Dialect dialect,
                       detail::DiagnosticList& out) {
  std::map<std::string, std::uint32_t> first_line;
  const auto check = [&](const std::string& key, std::uint32_t line, std::uint32_t column,
                         const std::string& label) {
    auto [it, inserted] = first_line.emplace(key, line);
    if (!inserted) {
      out.add(line, column,
              label + ": key is already used by the entry at line " + std::to_string(it->second));
    }
  };
  for (const RegisterSpec* spec : specs) {
    check(spec->key, spec->line, spec->column, detail::entry_label(*spec, dialect));
  }
  for (const CoilSpec* spec : coils) {
    check(spec->key, spec->line, spec->column, detail::coil_label(*spec, dialect));
  }
}

// A scale factor names a one-word signed number of the same map (SunSpec's "sunssf" points).
void check_scale_factors(const std::vector<const RegisterSpec*>& specs, Dialect dialect,
                         detail::DiagnosticList& out) {
  std::map<std::string_view, const RegisterSpec*> by_key;
  for (const RegisterSpec* spec : specs) by_key.emplace(spec->key, spec);
  for (const RegisterSpec* spec : specs) {
    if (spec->scale_factor.empty()) continue;
    const auto it = by_key.find(spec->scale_factor);
    const RegisterSpec* sf = it != by_key.end() ? it->second : nullptr;
    if (sf == nullptr || sf->kind != RegisterKind::Number || sf->float32 || sf->words != 1 ||
        sf->repeat != 1 || !sf->is_signed) {
      out.add(spec->line, spec->column,
              detail::entry_label(*spec, dialect) + ": scale_factor '" + spec->scale_factor +
                  "' must be the key of a one-word signed number register of this map");
    }
  }
}

// Singles may not share an address with singles, nor ranges with ranges; a single inside a
// range is how a documented register is carved out of an undocumented run.
void check_coverage(const std::vector<const RegisterSpec*>& specs, Dialect dialect,
                    detail::DiagnosticList& out) {
  std::map<std::uint16_t, const RegisterSpec*> singles;
  std::map<std::uint16_t, const RegisterSpec*> ranges;
  for (const RegisterSpec* spec : specs) {
    auto& owners = spec->repeat > 1 ? ranges : singles;
    bool reported = false;
    for_each_covered_address(*spec, dialect, [&](std::uint16_t address, auto, auto) {
      auto [it, inserted] = owners.emplace(address, spec);
      if (inserted || reported) return;
      reported = true;
      const RegisterSpec& other = *it->second;
      const std::string where(format_register_address(dialect, address).view());
      const std::string label = detail::entry_label(*spec, dialect);
      if (other.address == spec->address) {
        out.add(spec->line, spec->column,
                label + ": duplicate address, also defined at line " + std::to_string(other.line));
      } else {
        out.add(spec->line, spec->column,
                label + ": its word at " + where + " overlaps register '" + other.key + "' (line " +
                    std::to_string(other.line) + ")");
      }
    });
  }
}

// Entries of one table may not share an address.
void check_coil_addresses(const std::vector<const CoilSpec*>& specs, Dialect dialect,
                          detail::DiagnosticList& out) {
  std::map<std::pair<detail::CoilTable, std::int64_t>, const CoilSpec*> first_use;
  for (const CoilSpec* spec : specs) {
    auto [it, inserted] = first_use.emplace(std::pair{spec->table, spec->address}, spec);
    if (!inserted) {
      out.add(spec->line, spec->column,
              detail::coil_label(*spec, dialect) + ": duplicate address, also defined at line " +
                  std::to_string(it->second->line));
    }
  }
}

std::uint8_t decimals_for_scale(double scale) {
  for (std::uint8_t d = 0; d < 9; ++d) {
    const double shifted = scale * std::pow(10.0, d);
    if (std::fabs(shifted - std::round(shifted)) < 1e-9 * std::max(1.0, shifted)) return d;
  }
  return 9;
}

// A float32 carries fractions of whatever its scale is: without a map's say, three digits
// (230.100 V, 12.345 kWh) show them without pretending to the last bit of the mantissa.
std::uint8_t default_decimals(const RegisterSpec& spec) {
  constexpr std::uint8_t kFloatDecimals = 3;
  const std::uint8_t for_scale = decimals_for_scale(spec.scale);
  return spec.float32 ? std::max(for_scale, kFloatDecimals) : for_scale;
}

class MapLayout {
 public:
  MapLayout(const detail::MapHeaderSpec& header, std::vector<const RegisterSpec*> specs,
            const std::vector<const CoilSpec*>& coils)
      : data_(std::make_shared<RegisterMap::Data>()), specs_(std::move(specs)), coils_(coils) {
    data_->dialect = header.dialect;
    data_->step = static_cast<std::uint16_t>(address_step(header.dialect));
    data_->mode = header.mode;
    data_->title = header.title;
    data_->source_name = header.source_name;
  }

  std::shared_ptr<const RegisterMap::Data> run() {
    // Singles sort before a range starting at the same address, so find_address prefers them.
    std::stable_sort(specs_.begin(), specs_.end(),
                     [](const RegisterSpec* a, const RegisterSpec* b) {
                       if (a->address != b->address) return a->address < b->address;
                       return a->repeat < b->repeat;
                     });
    for (const RegisterSpec* spec : specs_) add_def(*spec);
    resolve_scale_factors();
    attach_tables();
    index_slots();
    add_coils();
    return data_;
  }

 private:
  struct TableSpan {
    std::size_t values_at, values_count, bits_at, bits_count;
  };

  std::string_view intern(const std::string& s) {
    data_->strings.push_back(s);
    return data_->strings.back();
  }

  void add_def(const RegisterSpec& spec) {
    RegisterDef def;
    def.address = to_u16(spec.address);
    def.words = to_u16(spec.words);
    def.repeat = to_u16(spec.repeat);
    def.kind = spec.kind;
    def.is_signed = spec.is_signed;
    def.pair_rule = spec.pair_rule.value_or(PairRule::FromOptions);
    def.word_order = spec.word_order.value_or(WordOrder::HighFirst);
    def.encoding = spec.float32 ? NumberEncoding::Float32 : NumberEncoding::Integer;
    def.scale = spec.scale;
    def.decimals =
        spec.decimals ? static_cast<std::uint8_t>(*spec.decimals) : default_decimals(spec);
    def.key = intern(spec.key);
    def.name = intern(spec.name);
    def.unit = intern(spec.unit);
    def.scale_factor = intern(spec.scale_factor);
    if (spec.no_value) {
      def.no_value = static_cast<std::uint32_t>(*spec.no_value);
      def.has_no_value = true;
    }
    def.line = spec.line;
    data_->defs.push_back(def);
    tables_.push_back(TableSpan{data_->enum_texts.size(), spec.values.size(),
                                data_->bit_names.size(), spec.bits.size()});
    add_tables(spec);
  }

  void add_tables(const RegisterSpec& spec) {
    const std::size_t values_at = data_->enum_texts.size();
    for (const auto& v : spec.values) {
      data_->enum_texts.push_back(EnumText{static_cast<std::uint32_t>(v.number), intern(v.text)});
    }
    std::sort(data_->enum_texts.begin() + static_cast<std::ptrdiff_t>(values_at),
              data_->enum_texts.end(),
              [](const EnumText& a, const EnumText& b) { return a.value < b.value; });
    const std::size_t bits_at = data_->bit_names.size();
    for (const auto& b : spec.bits) {
      data_->bit_names.push_back(BitName{static_cast<std::uint8_t>(b.number), intern(b.text)});
    }
    std::sort(data_->bit_names.begin() + static_cast<std::ptrdiff_t>(bits_at),
              data_->bit_names.end(),
              [](const BitName& a, const BitName& b) { return a.index < b.index; });
  }

  void resolve_scale_factors() {
    std::map<std::string_view, std::uint16_t> address_of;
    for (const RegisterDef& def : data_->defs) address_of.emplace(def.key, def.address);
    for (RegisterDef& def : data_->defs) {
      const auto found = address_of.find(def.scale_factor);
      if (!def.has_scale_factor() || found == address_of.end()) continue;
      def.scale_factor_address = found->second;
      data_->has_scale_factors = true;
      for (RegisterDef& sf : data_->defs) sf.is_scale_factor |= sf.key == def.scale_factor;
    }
  }

  // Only now are the tables complete, so their spans no longer move.
  void attach_tables() {
    for (std::size_t i = 0; i < data_->defs.size(); ++i) {
      const TableSpan& t = tables_[i];
      data_->defs[i].values =
          std::span<const EnumText>(data_->enum_texts).subspan(t.values_at, t.values_count);
      data_->defs[i].bits =
          std::span<const BitName>(data_->bit_names).subspan(t.bits_at, t.bits_count);
    }
  }

  void index_slots() {
    std::map<std::uint16_t, RegisterSlotEntry> slots;
    for (int pass = 0; pass < 2; ++pass) {  // ranges first, so that singles overwrite them
      for (std::size_t i = 0; i < specs_.size(); ++i) {
        const bool range = specs_[i]->repeat > 1;
        if (range != (pass == 0)) continue;
        for_each_covered_address(
            *specs_[i], data_->dialect,
            [&](std::uint16_t address, std::uint16_t instance, std::uint16_t word) {
              slots[address] =
                  RegisterSlotEntry{address, static_cast<std::uint16_t>(i), word, instance};
            });
      }
    }
    data_->slots.reserve(slots.size());
    for (const auto& entry : slots) data_->slots.push_back(entry.second);
    index_addresses();
  }

  void index_addresses() {
    const auto& slots = data_->slots;
    if (slots.empty()) return;
    data_->first_address = slots.front().address;
    data_->slot_by_address.assign(slots.back().address - slots.front().address + 1u,
                                  RegisterMap::Data::kNoSlot);
    for (std::size_t i = 0; i < slots.size(); ++i) {
      data_->slot_by_address[slots[i].address - data_->first_address] =
          static_cast<std::uint32_t>(i);
    }
  }

  void add_coils() {
    for (const CoilSpec* spec : coils_) {
      auto& into = spec->table == detail::CoilTable::Coils ? data_->coils : data_->discrete_inputs;
      into.push_back(
          CoilDef{to_u16(spec->address), intern(spec->key), intern(spec->name), spec->line});
    }
    for (auto* table : {&data_->coils, &data_->discrete_inputs}) {
      std::sort(table->begin(), table->end(),
                [](const CoilDef& a, const CoilDef& b) { return a.address < b.address; });
    }
  }

  std::shared_ptr<RegisterMap::Data> data_;
  std::vector<const RegisterSpec*> specs_;
  const std::vector<const CoilSpec*>& coils_;
  std::vector<TableSpan> tables_;
};

}  // namespace

RegisterMapResult RegisterMapBuilder::build(std::vector<MapDiagnostic> earlier) && {
  detail::DiagnosticList problems{header_.source_name, std::move(earlier)};
  std::vector<const RegisterSpec*> valid;
  for (const RegisterSpec& spec : specs_) {
    const std::size_t before = problems.items.size();
    detail::check_register_entry(spec, header_.dialect, problems);
    if (problems.items.size() == before) valid.push_back(&spec);
  }
  std::vector<const CoilSpec*> valid_coils;
  for (const CoilSpec& spec : coil_specs_) {
    const std::size_t before = problems.items.size();
    detail::check_coil_entry(spec, header_.dialect, problems);
    if (problems.items.size() == before) valid_coils.push_back(&spec);
  }
  check_keys_unique(valid, valid_coils, header_.dialect, problems);
  check_coverage(valid, header_.dialect, problems);
  if (!defer_scale_factors_) check_scale_factors(valid, header_.dialect, problems);
  check_coil_addresses(valid_coils, header_.dialect, problems);
  if (!problems.empty()) {
    std::stable_sort(
        problems.items.begin(), problems.items.end(),
        [](const MapDiagnostic& a, const MapDiagnostic& b) { return a.line < b.line; });
    return RegisterMapResult::failure(std::move(problems.items));
  }
  return RegisterMap(MapLayout(header_, std::move(valid), valid_coils).run());
}

}  // namespace pvtap

namespace pvtap::detail {

RegisterSpec spec_of(const RegisterDef& def) {
  RegisterSpec spec;
  spec.address = def.address;
  spec.words = def.words;
  spec.repeat = def.repeat;
  spec.kind = def.kind;
  spec.is_signed = def.is_signed;
  if (def.words == 2 && !def.is_float()) spec.pair_rule = def.pair_rule;
  if (def.word_order != WordOrder::HighFirst) spec.word_order = def.word_order;
  spec.float32 = def.is_float();
  spec.decimals = def.decimals;
  spec.scale = def.scale;
  spec.key = std::string(def.key);
  spec.name = std::string(def.name);
  spec.unit = std::string(def.unit);
  spec.scale_factor = std::string(def.scale_factor);
  if (def.has_no_value) spec.no_value = def.no_value;
  for (const EnumText& v : def.values) spec.values.push_back({v.value, std::string(v.text), 0, 0});
  for (const BitName& b : def.bits) spec.bits.push_back({b.index, std::string(b.name), 0, 0});
  spec.line = def.line;
  return spec;
}

CoilSpec spec_of(const CoilDef& def, CoilTable table) {
  CoilSpec spec;
  spec.table = table;
  spec.address = def.address;
  spec.key = std::string(def.key);
  spec.name = std::string(def.name);
  spec.line = def.line;
  return spec;
}

}  // namespace pvtap::detail
