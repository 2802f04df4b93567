#include "settings/station_maps.h"

#include <epan/packet.h>
#include <epan/uat.h>
#include <wsutil/report_message.h>

#include <algorithm>
#include <cstring>
#include <exception>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "settings/map_file.h"
#include "settings/preferences.h"
#include "settings/register_maps.h"
#include "settings/station_list.h"
#include "wireshark_api/uat_types.h"

namespace pvtap::dissector {
namespace {

// StationMapRow: one row of the table as Wireshark keeps it (plain C strings it copies).
struct StationMapRow {
  char* stations;
  char* file;
};

StationMapRow* g_rows = nullptr;
guint g_row_count = 0;

// RowTexts: the table's rows as text (stations, file), to tell whether the table changed.
using RowTexts = std::vector<std::pair<std::string, std::string>>;

// The maps the rows gave, by station, in the order the rows first named the stations, and the
// rows they were built from.
std::vector<std::pair<std::uint8_t, RegisterMap>> g_station_maps;
RowTexts g_applied_rows;

std::string_view text_of(const char* text) {
  return text != nullptr ? std::string_view(text) : std::string_view();
}

// LoadedMap: a station map read from its file, or why it cannot be one.
struct LoadedMap {
  std::optional<RegisterMap> map;
  std::string problem;
};

LoadedMap load_station_map(std::string_view path) {
  if (path.empty()) return {std::nullopt, "no map file given"};
  const std::string file(path);
  RegisterMapResult loaded = read_map_file(file);
  if (!loaded) return {std::nullopt, "the register map does not load:\n" + loaded.error_text()};
  const Dialect d = loaded->dialect();
  if (!modbus_family(d)) {
    return {std::nullopt, file + " is a " + std::string(to_string(d)) +
                              " map; a station's map must be a gsl or modbus map"};
  }
  return {loaded.value(), {}};
}

// Field and record checks: Wireshark shows the message beside the row (GUI) or with the
// table's file and line (tshark), and keeps a row that fails out of the table's records.
UatVerdict check_stations(void*, const char* text, unsigned length, const void*, const void*,
                          char** error) {
  const StationList list = read_station_list({text, length});
  if (list.ok()) return TRUE;
  *error = g_strdup(list.problem.c_str());
  return FALSE;
}

UatVerdict check_file(void*, const char* text, unsigned length, const void*, const void*,
                      char** error) {
  const LoadedMap loaded = load_station_map({text, length});
  if (loaded.map) return TRUE;
  *error = g_strdup(loaded.problem.c_str());
  return FALSE;
}

UatVerdict check_row(void* record, char** error) {
  const auto* row = static_cast<const StationMapRow*>(record);
  const std::string_view stations = text_of(row->stations);
  const std::string_view file = text_of(row->file);
  return check_stations(record, stations.data(), static_cast<unsigned>(stations.size()), nullptr,
                        nullptr, error) &&
         check_file(record, file.data(), static_cast<unsigned>(file.size()), nullptr, nullptr,
                    error);
}

// Column: which field the shared set and text callbacks handle (their `fld_data`).
enum class Column : std::uint8_t { Stations, File };
constexpr Column kStationsColumn = Column::Stations;
constexpr Column kFileColumn = Column::File;

char** field_of(void* record, const void* column) {
  auto* row = static_cast<StationMapRow*>(record);
  return *static_cast<const Column*>(column) == Column::File ? &row->file : &row->stations;
}

void set_text(void* record, const char* text, unsigned length, const void*, const void* which) {
  char** field = field_of(record, which);
  g_free(*field);
  *field = g_strndup(text, length);
}

void text_out(void* record, char** out, unsigned* length, const void*, const void* which) {
  const char* text = *field_of(record, which);
  *out = g_strdup(text != nullptr ? text : "");
  *length = static_cast<unsigned>(std::strlen(*out));
}

void* copy_row(void* destination, const void* source, size_t) {
  auto* to = static_cast<StationMapRow*>(destination);
  const auto* from = static_cast<const StationMapRow*>(source);
  to->stations = g_strdup(from->stations);
  to->file = g_strdup(from->file);
  return to;
}

void free_row(void* record) {
  auto* row = static_cast<StationMapRow*>(record);
  g_free(row->stations);
  g_free(row->file);
  row->stations = nullptr;
  row->file = nullptr;
}

void report_row(std::size_t index, const std::pair<std::string, std::string>& row,
                const std::string& problem) {
  report_warning(
      "pvtap: station register maps, row %zu (stations \"%s\", file \"%s\") is left out: %s",
      index + 1, row.first.c_str(), row.second.c_str(), problem.c_str());
}

// As pvtap's --map STATION=FILE: an extend map is laid over what the station had so far
// (a map of the same dialect), else over the map in effect for its dialect.
std::optional<std::string> give_station(std::uint8_t station, const RegisterMap& map) {
  auto own = std::find_if(g_station_maps.begin(), g_station_maps.end(),
                          [station](const auto& entry) { return entry.first == station; });
  const bool stacks = own != g_station_maps.end() && own->second.dialect() == map.dialect();
  const RegisterMapResult stacked =
      stack_register_map(stacks ? own->second : effective_map(map.dialect()), map);
  if (!stacked) return stacked.error_text();
  if (own != g_station_maps.end()) {
    own->second = stacked.value();
  } else {
    g_station_maps.emplace_back(station, stacked.value());
  }
  return std::nullopt;
}

void apply_row(std::size_t index, const std::pair<std::string, std::string>& row) {
  const StationList list = read_station_list(row.first);
  if (!list.ok()) return report_row(index, row, list.problem);
  const LoadedMap loaded = load_station_map(row.second);
  if (!loaded.map) return report_row(index, row, loaded.problem);
  for (const std::uint8_t station : list.stations) {
    if (auto problem = give_station(station, *loaded.map)) return report_row(index, row, *problem);
  }
}

// The rows Wireshark holds now: only those that passed the checks.
RowTexts current_rows() {
  RowTexts rows;
  for (guint i = 0; i < g_row_count; ++i) {
    rows.emplace_back(text_of(g_rows[i].stations), text_of(g_rows[i].file));
  }
  return rows;
}

// The maps are read again and the decoder rebuilt. Wireshark then dissects again, and every
// bus session starts over with the new decoder (release_bus_tracks), so the stations'
// dialects follow the new maps.
void rebuild(const RowTexts& rows) {
  g_station_maps.clear();
  g_applied_rows = rows;
  try {
    for (std::size_t i = 0; i < rows.size(); ++i) apply_row(i, rows[i]);
  } catch (const std::exception& e) {
    report_warning("pvtap: reading the station register maps failed: %s", e.what());
  }
  apply_preferences();
}

// The table changed: edited, set with -o, or loaded at start-up.
void apply_rows() {
  rebuild(current_rows());
}

// Before each dissection of a file. Wireshark skips the table's change callback when its file
// had a bad row, yet keeps the good ones: they are applied here.
void catch_up_with_rows() {
  RowTexts rows = current_rows();
  if (rows != g_applied_rows) rebuild(rows);
}

// The table's columns, as the table's file lists them: "10,11","/path/meter.toml".
uat_field_t g_fields[] = {
    {"stations",
     "Stations",
     PT_TXTMOD_STRING,
     {check_stations, set_text, text_out},
     {nullptr, nullptr, nullptr},
     &kStationsColumn,
     "Station addresses that use the map: 10, or several as 10,11 (1 to 247)",
     nullptr},
    {"map_file",
     "Register map file",
     PT_TXTMOD_FILENAME,
     {check_file, set_text, text_out},
     {nullptr, nullptr, nullptr},
     &kFileColumn,
     "A register map in pvtap's TOML format (dialect gsl or modbus)",
     nullptr},
    UAT_END_FIELDS,
};

}  // namespace

void register_station_map_table(module_t* module) {
  uat_t* table = uat_new("Station register maps", sizeof(StationMapRow), "pvtap_station_maps", TRUE,
                         &g_rows, &g_row_count, UAT_AFFECTS_DISSECTION, nullptr, copy_row,
                         check_row, free_row, apply_rows, nullptr, g_fields);
  prefs_register_uat_preference(module, "station_maps", "Station register maps",
                                "A register map per station (a meter on a bus of inverters): "
                                "its GSL and Modbus frames decode with it, and the station "
                                "speaks the map's dialect, as pvtap audit --map STATION=FILE",
                                table);
  register_init_routine(catch_up_with_rows);
}

void use_station_maps(RegisterDecoder& decoder) {
  for (const auto& [station, map] : g_station_maps) decoder.use_station_map(station, map);
}

}  // namespace pvtap::dissector
