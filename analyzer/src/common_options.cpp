#include "common_options.h"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <string>
#include <vector>

#include "pvtap/register_decoder.h"
#include "pvtap/register_map.h"
#include "user_map_folder.h"

namespace pvtap::analyzer {
namespace {

DialectSet dialects_named(const std::string& name) {
  if (name == "ascii") return DialectSet::only(Dialect::Ascii);
  if (name == "hybrid") return DialectSet::only(Dialect::Hybrid);
  if (name == "gsl") return DialectSet::only(Dialect::Gsl);
  return DialectSet::all();
}

}  // namespace

void add_protocol_options(CLI::App& audit, AuditOptions& o, BaudRange baud_range) {
  audit.add_option("--dialect", o.dialect, "dialect(s) to recognize: auto|ascii|hybrid|gsl")
      ->check(CLI::IsMember({"auto", "ascii", "hybrid", "gsl"}).description(""))
      ->type_name("NAME")
      ->default_str("auto");
  const std::string baud_help = "bus baud rate (" + std::to_string(baud_range.min) + " to " +
                                std::to_string(baud_range.max) + "), for the timing rules";
  audit.add_option("--baud", o.baud, baud_help)
      ->check(CLI::Range(baud_range.min, baud_range.max).description(""))
      ->type_name("BAUD")
      ->default_str("9600");
  audit
      .add_option("--timeout", o.timeout,
                  "seconds a request may wait for its reply before it counts as a timeout")
      ->check(CLI::Range(0.001, 3600.0).description(""))
      ->type_name("SECONDS")
      ->default_str("1");
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
  audit
      .add_option("--map", o.maps,
                  "register map (TOML, see protocols/maps/README.md) replacing or extending the "
                  "built-in map of its dialect; repeatable; read after the user's maps in "
                  "~/.config/pvtap/maps/*.toml")
      ->type_name("FILE")
      ->allow_extra_args(false);
}

void add_output_options(CLI::App& audit, AuditOptions& o) {
  audit.add_option("--format", o.format_name, "output format: text, jsonl or csv")
      ->check(CLI::IsMember({"text", "jsonl", "csv"}).description(""))
      ->type_name("FORMAT")
      ->default_str("text");
  audit.add_flag("--summary-only", o.summary_only, "print only the report, no per-frame lines");
  audit
      .add_option("--write", o.write_path,
                  "also write the frames (and noise runs) to FILE as pcap with link type 252 "
                  "(exported PDUs, dissector \"pvtap\"), for Wireshark with pvtap's plugin")
      ->type_name("FILE");
  audit
      .add_option("--fail-on", o.fail_on,
                  "'errors': exit 1 when bad checks, timeouts or exceptions were found "
                  "(without it, findings never change the exit status)")
      ->check(CLI::IsMember({"errors"}).description(""))
      ->type_name("errors");
}

bool load_maps(const AuditOptions& o, RegisterDecoder& decoder) {
  // The user's own maps first, so that a --map file is laid over them.
  std::vector<std::string> paths = user_map_files(user_map_folder());
  paths.insert(paths.end(), o.maps.begin(), o.maps.end());
  for (const std::string& path : paths) {
    const RegisterMapResult loaded = load_register_map_file(path);
    // Several files stack in the order given, as the plugin stacks its folder's files.
    const RegisterMapResult resolved =
        loaded ? stack_register_map(decoder.map(loaded->dialect()), loaded.value()) : loaded;
    const RegisterMapResult& failed = loaded ? resolved : loaded;
    if (!loaded || !resolved) {
      std::fprintf(stderr, "pvtap: %s: bad register map\n%s", path.c_str(),
                   failed.error_text().c_str());
      return false;
    }
    decoder.use_map(resolved.value());
  }
  return true;
}

void apply_choices(AuditOptions& o) {
  o.dialects = dialects_named(o.dialect);
  o.gsl_ids = o.gsl_id_reading == "hex" ? GslIdReading::Hex : GslIdReading::Decimal;
  o.format = o.format_name == "jsonl" ? OutputFormat::Jsonl
             : o.format_name == "csv" ? OutputFormat::Csv
                                      : OutputFormat::Text;
  o.fail_on_errors = o.fail_on == "errors";
}

}  // namespace pvtap::analyzer
