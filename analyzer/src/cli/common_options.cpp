#include "cli/common_options.h"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "cli/exit_status.h"
#include "cli/map_files.h"
#include "pvtap/registers/register_decoder.h"
#include "pvtap/registers/register_map.h"

namespace pvtap::analyzer {
namespace {

// "auto", or a comma-separated list of dialect names ("gsl,modbus").
std::optional<DialectSet> dialects_named(std::string_view names) {
  if (names == "auto") return DialectSet::all();
  DialectSet set = DialectSet::none();
  while (!names.empty()) {
    const std::size_t comma = names.find(',');
    const auto d = dialect_named(names.substr(0, comma));
    if (!d) return std::nullopt;
    // "modbus,gsl": a shared code nothing else decides is plain Modbus (section 6's order).
    set = set.then(*d);
    names = comma == std::string_view::npos ? std::string_view{} : names.substr(comma + 1);
  }
  if (set == DialectSet::none()) return std::nullopt;
  return set;
}

}  // namespace

void add_protocol_options(CLI::App& audit, CommonOptions& o, BaudRange baud_range) {
  audit
      .add_option("--dialect", o.dialect,
                  "dialect(s) to recognize: auto, or a comma-separated list of ascii, hybrid, "
                  "gsl, modbus (auto is all four; modbus is every other Modbus RTU device). "
                  "A GSL code that nothing else labels is taken as the earlier of gsl and "
                  "modbus in the list (auto: gsl)")
      ->check(CLI::Validator(
          [](std::string& value) {
            return dialects_named(value) ? std::string{}
                                         : "expected auto or a list of ascii,hybrid,gsl,modbus";
          },
          "", "dialect list"))
      ->type_name("NAME")
      ->default_str("auto")
      ->each([&o](const std::string&) { o.given.dialects = true; });
  const std::string baud_help = "bus baud rate (" + std::to_string(baud_range.min) + " to " +
                                std::to_string(baud_range.max) + "), for the timing rules";
  audit.add_option("--baud", o.baud, baud_help)
      ->check(CLI::Range(baud_range.min, baud_range.max).description(""))
      ->type_name("BAUD")
      ->default_str("9600")
      ->each([&o](const std::string&) { o.given.baud = true; });
  audit
      .add_option("--timeout", o.timeout,
                  "seconds a request may wait for its reply before it counts as a timeout")
      ->check(CLI::Range(0.001, 3600.0).description(""))
      ->type_name("SECONDS")
      ->default_str("1")
      ->each([&o](const std::string&) { o.given.timeout = true; });
  audit
      .add_option("--gateway-gap", o.gateway_gap_ms,
                  "milliseconds of silence between two TCP/UDP segments of one direction that "
                  "prove a frame boundary: a gateway packs bytes for a shorter time than this, so "
                  "a longer pause was silence on the bus (0: segment times prove nothing)")
      ->check(CLI::Range(0.0, 60000.0).description(""))
      ->type_name("MS")
      ->default_str("50");
  audit
      .add_option("--gsl-ids", o.gsl_id_reading,
                  "how GSL register IDs go on the wire: decimal (ID 1050 is 0x041A) or hex "
                  "(1050 is 0x1050)")
      ->check(CLI::IsMember({"decimal", "hex"}).description(""))
      ->type_name("READING")
      ->default_str("decimal");
  audit.add_flag(
      "--no-sunspec", o.no_sunspec,
      "do not decode SunSpec devices by their models: a station whose replies show the \"SunS\" "
      "marker at 40000, 50000 or 0 and the model headers after it is otherwise decoded with "
      "the published models' points and scale factors, learned from what its master reads");
  audit
      .add_option("--map", o.maps,
                  "register map (TOML; the format and the built-in maps are in " PVTAP_MAPS_DIR
                  "). FILE replaces or extends "
                  "the built-in map of its dialect, read after the user's maps in "
                  "~/.config/pvtap/maps/*.toml. STATION=FILE gives a gsl or modbus map to one "
                  "station (10=meter.toml) or several (10,11=meter.toml), 1 to 247: their frames "
                  "decode with it, e.g. an energy meter on a bus of inverters; repeatable")
      ->type_name("FILE|STATION=FILE")
      ->allow_extra_args(false);
}

void add_output_options(CLI::App& audit, CommonOptions& o) {
  audit.add_option("--format", o.format_name, "output format: text, jsonl or csv")
      ->check(CLI::IsMember({"text", "jsonl", "csv"}).description(""))
      ->type_name("FORMAT")
      ->default_str("text");
  audit.add_flag("--summary-only", o.summary_only, "print only the report, no per-frame lines");
  audit
      .add_option("--write", o.write_path,
                  "also write the frames (and noise runs) to FILE as pcap with link type 252 "
                  "(exported PDUs, dissector \"pvtap\"), for Wireshark with pvtap's plugin; "
                  "pvtap audit FILE gives this run's verdicts again")
      ->type_name("FILE");
  audit
      .add_option("--fail-on", o.fail_on,
                  "'errors': exit 1 when bad checks, timeouts or exceptions were found, or no "
                  "frame at all; 'empty': exit 1 only when no frame was found (without it, "
                  "findings never change the exit status)")
      ->check(CLI::IsMember({"errors", "empty"}).description(""))
      ->type_name("errors|empty");
  add_values_options(audit, o);
  add_html_options(audit, o);
}

void add_values_options(CLI::App& command, CommonOptions& o) {
  CLI::Option* values = command.add_option(
      "--values", o.values_path,
      "also write every register value of a good reply to a good request to FILE, "
      "one row per value (ts, bus, station, dialect, register, key, name, value, "
      "unit), for duckdb, pandas, a spreadsheet or Telegraf");
  values->type_name("FILE");
  command
      .add_option("--values-format", o.values_format_name,
                  "format of --values: csv (with a header), jsonl, or influx (InfluxDB line "
                  "protocol: measurement pvtap, tags bus/station/dialect/key, field value, "
                  "time in ns; numeric registers only; POST it to InfluxDB's "
                  "/write?db=DB&precision=ns)")
      ->check(CLI::IsMember({"csv", "jsonl", "influx"}).description(""))
      ->needs(values)
      ->type_name("FORMAT")
      ->default_str("csv");
}

void add_html_options(CLI::App& command, CommonOptions& o) {
  CLI::Option* html = command.add_option(
      "--html", o.html_path,
      "also write the report to FILE as one self-contained HTML page (no network "
      "needed): health tiles, stations, a timeline of every request, reply and "
      "finding, bus load, latency, polling and register values as zoomable charts");
  html->type_name("FILE");
  command
      .add_option("--plot", o.plot_keys,
                  "register keys (e.g. pv_power,energy_today) the --html page charts; default: "
                  "every numeric register that changed")
      ->needs(html)
      ->type_name("KEY,...")
      ->delimiter(',')
      ->allow_extra_args(false);
}

namespace {

// The map in the file, or nullopt after saying why not (the loader's diagnostics).
std::optional<RegisterMap> read_map_or_say_why(const std::string& path,
                                               const RegisterMapResult& loaded) {
  if (loaded) return loaded.value();
  const auto& problems = loaded.diagnostics();
  if (problems.size() == 1 && problems.front().line == 0) {
    // The file itself (missing, no permission): no word on a map that was never read.
    std::fprintf(stderr, "pvtap: %s: %s\n", path.c_str(), problems.front().message.c_str());
  } else {
    std::fprintf(stderr, "pvtap: %s: bad register map\n%s\n", path.c_str(),
                 loaded.error_text().c_str());
  }
  return std::nullopt;
}

// Several files stack in the order given, as the plugin stacks its folder's files.
bool load_dialect_map(const std::string& path, RegisterDecoder& decoder) {
  const RegisterMapResult loaded = read_register_map_file(path);
  if (!loaded) return read_map_or_say_why(path, loaded).has_value();
  const RegisterMapResult resolved =
      stack_register_map(decoder.map(loaded->dialect()), loaded.value());
  const std::optional<RegisterMap> map = read_map_or_say_why(path, resolved);
  if (map) decoder.use_map(*map);
  return map.has_value();
}

// A station's map stacks like a dialect's: an extend map is laid over what the station had
// so far, or over the map in effect for its dialect.
bool load_station_map(const StationMapArgument& arg, RegisterDecoder& decoder) {
  const RegisterMapResult loaded = read_register_map_file(arg.path);
  if (!loaded) return read_map_or_say_why(arg.path, loaded).has_value();
  if (!modbus_family(loaded->dialect())) {
    std::fprintf(stderr, "pvtap: %s: a station's map must be a gsl or modbus map, not %s\n",
                 arg.path.c_str(), std::string(to_string(loaded->dialect())).c_str());
    return false;
  }
  for (const std::uint8_t station : arg.stations) {
    const RegisterMap* own = decoder.station_map(station);
    const bool stacks = own != nullptr && own->dialect() == loaded->dialect();
    const RegisterMapResult resolved =
        stack_register_map(stacks ? *own : decoder.map(loaded->dialect()), loaded.value());
    const std::optional<RegisterMap> map = read_map_or_say_why(arg.path, resolved);
    if (!map) return false;
    decoder.use_station_map(station, *map);
  }
  return true;
}

}  // namespace

bool load_maps(const CommonOptions& o, RegisterDecoder& decoder) {
  // The user's own maps first, so that a --map file is laid over them; station maps last,
  // so that an extend map for a station is laid over its dialect's map as the files made it.
  std::vector<std::string> paths = user_map_files(user_map_folder());
  std::vector<StationMapArgument> station_maps;
  for (const std::string& value : o.maps) {
    std::optional<StationMapArgument> arg = read_station_map_argument(value);
    if (!arg) {
      paths.push_back(value);
    } else if (!arg->problem.empty()) {
      std::fprintf(stderr, "pvtap: --map %s: %s\n", value.c_str(), arg->problem.c_str());
      return false;
    } else {
      station_maps.push_back(std::move(*arg));
    }
  }
  for (const std::string& path : paths) {
    if (!load_dialect_map(path, decoder)) return false;
  }
  for (const StationMapArgument& arg : station_maps) {
    if (!load_station_map(arg, decoder)) return false;
  }
  return true;
}

int findings_status(const CommonOptions& o, const AuditReport& report) {
  if (o.fail_on_errors && has_findings(report)) return kExitFindings;
  return o.fail_on_empty && found_no_frame(report) ? kExitFindings : kExitOk;
}

void apply_choices(CommonOptions& o) {
  o.dialects = dialects_named(o.dialect).value_or(DialectSet::all());
  o.gsl_ids = o.gsl_id_reading == "hex" ? GslIdReading::Hex : GslIdReading::Decimal;
  o.format = o.format_name == "jsonl" ? OutputFormat::Jsonl
             : o.format_name == "csv" ? OutputFormat::Csv
                                      : OutputFormat::Text;
  o.fail_on_errors = o.fail_on == "errors";
  o.fail_on_empty = o.fail_on == "errors" || o.fail_on == "empty";
  o.values_format = o.values_format_name == "jsonl"    ? ValuesFormat::Jsonl
                    : o.values_format_name == "influx" ? ValuesFormat::Influx
                                                       : ValuesFormat::Csv;
}

PipelineSettings pipeline_settings(const CommonOptions& o) {
  PipelineSettings s;
  s.dialects = o.dialects;
  s.baud = o.baud;
  s.timeout = o.timeout;
  s.gateway_gap_ms = o.gateway_gap_ms;
  s.ports = o.ports;
  // --values and --html need the values of every frame even when stdout shows none.
  s.decode_values =
      !o.summary_only || !o.values_path.empty() || !o.html_path.empty() || o.mqtt.active();
  s.gsl_ids = o.gsl_ids;
  s.given = o.given;
  return s;
}

OutputSettings output_settings(const CommonOptions& o) {
  OutputSettings s;
  s.format = o.format;
  s.summary_only = o.summary_only;
  s.write_path = o.write_path;
  s.written_run = RunFacts{o.dialects, o.baud, o.timeout, {}};
  s.files = FileOutputSettings{o.values_path, o.values_format, o.html_path, o.plot_keys};
  s.mqtt = o.mqtt;
  s.mqtt.lone_serial_bus = kSerialBusName;
  return s;
}

}  // namespace pvtap::analyzer
