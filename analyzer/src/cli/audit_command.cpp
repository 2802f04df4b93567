#include "cli/audit_command.h"

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "cli/audit_input.h"
#include "cli/common_options.h"
#include "cli/exit_status.h"
#include "cli/mqtt_command_options.h"
#include "pipeline/pipeline.h"
#include "pvtap/pcap/link_types.h"
#include "pvtap/session/draft_map.h"
#include "run/run_output.h"

namespace pvtap::analyzer {
namespace {

const char* const kDescription =
    "Audit captured inverter bus traffic: every frame with its check verdict and decoded "
    "values, then a report of bad checks, timeouts, exceptions, noise, data loss, latency, "
    "polling and bus timing, and the latest value of every register per station.";

std::string footer_text() {
  return "\nInputs (told by their first bytes, whatever their names; captures by link type):\n"
         "  gateway traffic    Ethernet, Linux cooked (SLL, SLL2), raw IP and loopback captures\n"
         "                     of a serial-to-TCP gateway (TCP or UDP). TCP is reassembled per\n"
         "                     direction; lost segments are reported as data-loss gaps. The side\n"
         "                     on the gateway port is the slave side.\n"
         "  serial captures    USER0-USER15 and RTAC serial: raw bus bytes in chunks.\n"
         "  exported PDUs      link type 252 as written by --write.\n"
         "  --raw FILE         a plain dump of bus bytes (cat /dev/ttyUSB0 > FILE), no time.\n"
         "  logic recordings   a sigrok session (.sr), a VCD file (.vcd) or a logic CSV (.csv,\n"
         "                     a column per channel as sigrok-cli -O csv writes it; give its\n"
         "                     --samplerate), read with libsigrok: each channel with UART\n"
         "                     traffic is a bus; its baud, parity, stop bits and idle level are\n"
         "                     found from the samples (--channels names the channels), and\n"
         "                     t1.5/t3.5 are judged at the sample clock. One recording at a time.\n"
         "  Several FILEs are one capture, read in the order of their records' times whatever\n"
         "                     the order given (ring files: cap, cap1 .. cap10); files that\n"
         "                     overlap in time are merged. Files that repeat each other's\n"
         "                     records are refused; a damaged or unreadable file is named and\n"
         "                     the others are read. A clock that steps back inside a file is a\n"
         "                     finding (its records are moved on to follow the step).\n"
         "\nOutput on stdout: frames (and timeouts, noise, gaps) in the chosen format, then the\n"
         "report. jsonl ends with a {\"type\":\"summary\",...} line; csv holds rows only (use\n"
         "--summary-only for the report).\n"
         "\nFiles besides stdout: --values FILE writes every decoded register value of a good\n"
         "reply as a time series (csv, jsonl or InfluxDB line protocol); --html FILE writes the\n"
         "report as one self-contained page with zoomable charts (open it from disk, no network).\n"
         "\nExit status: 0 done; 1 findings (bad checks, timeouts, exceptions, or no frame at\n"
         "all) with --fail-on errors, no frame with --fail-on empty; 2 usage error, or an input\n"
         "unreadable, damaged or repeated (what could be read is reported first).\n"
         "\nExamples:\n"
         "  pvtap audit site.pcapng\n"
         "  pvtap audit --format jsonl --port 4001 gateway.pcap | jq 'select(.check==\"bad\")'\n"
         "  pvtap audit --summary-only --fail-on errors --timeout 0.5 bus.pcap\n"
         "  pvtap audit --raw ttyUSB0.bin --dialect gsl --baud 4800\n"
         "  pvtap audit --write frames.pcap capture.pcap   (open frames.pcap in Wireshark)\n"
         "  pvtap audit --summary-only --html day.html --values day.csv site.pcap\n"
         "  pvtap audit --summary-only --values site.lp --values-format influx site.pcap\n"
         "  pvtap audit --summary-only --mqtt mqtt://broker.lan day.pcapng  (back-fill a broker\n"
         "      with the day's values and events, stamped with their capture times)\n"
         "\nSupported link types: " +
         supported_link_types_text() + "\n";
}

void add_input_options(CLI::App& audit, AuditOptions& o) {
  audit
      .add_option("FILE", o.captures,
                  "capture(s) or a logic recording to audit: pcap, pcapng, a sigrok session, "
                  "VCD or logic CSV (see Inputs below)")
      ->type_name("FILE");
  audit.add_option("--raw", o.raw_dumps, "a plain dump of bus bytes (no timestamps); repeatable")
      ->type_name("FILE")
      ->allow_extra_args(false);
  add_reading_options(audit, o);
}

}  // namespace

CLI::App* add_audit_command(CLI::App& app, AuditOptions& options) {
  CLI::App* audit = app.add_subcommand("audit", kDescription);
  audit->footer(footer_text() + kMqttHelpFooter);
  add_input_options(*audit, options);
  add_protocol_options(*audit, options, kBaudRange);
  add_output_options(*audit, options);
  audit->add_option("--draft-map", options.draft_map_dir,
                    "write DIR/station-N.toml, a draft register map of each station with "
                    "registers no map names, their types inferred (load it with --map N=FILE)");
  add_mqtt_options(*audit, options.mqtt);
  return audit;
}

namespace {

// --draft-map DIR: station-N.toml for each station with inferred blocks. A file that cannot be
// written is named on stderr; the audit goes on.
void write_draft_maps(const AuditOptions& options, const AuditReport& report) {
  if (options.draft_map_dir.empty()) return;
  const std::string source = !options.captures.empty()    ? options.captures.front()
                             : !options.raw_dumps.empty() ? options.raw_dumps.front()
                                                          : std::string("the capture");
  std::error_code error;
  std::filesystem::create_directories(options.draft_map_dir, error);
  for (const BusFindings& bus : report.buses) {
    for (const StationSummary& s : bus.report.stations) {
      const std::string text = draft_register_map(s, source);
      if (text.empty()) continue;
      std::string name = "station-" + std::to_string(s.station);
      // Stations of several buses may share an address: the bus keeps their files apart.
      if (report.buses.size() > 1 && !bus.name.empty()) {
        std::string safe;
        for (const char c : bus.name) safe += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
        name = safe + "-" + name;
      }
      const std::string path =
          (std::filesystem::path(options.draft_map_dir) / (name + ".toml")).string();
      std::ofstream file(path, std::ios::binary);
      file << text;
      file.close();
      if (!file) {
        std::fprintf(stderr, "pvtap: cannot write the draft map %s: %s\n", path.c_str(),
                     error ? error.message().c_str() : std::strerror(errno));
      }
    }
  }
}

}  // namespace

int run_audit(AuditOptions& options) {
  apply_choices(options);
  RegisterDecoder decoder(DecoderOptions{options.gsl_ids, PairRule::Binary, !options.no_sunspec});
  if (!load_maps(options, decoder)) return kExitBadInput;
  options.progress = ::isatty(STDERR_FILENO) == 1;
  if (options.threads == 0) options.threads = default_threads();
  OutputStream out(stdout);
  const int status = audit(options, decoder, out);
  out.flush();
  if (out.failed()) {
    std::fprintf(stderr, "pvtap: cannot write the output\n");
    return kExitBadInput;
  }
  return status;
}

int audit(const AuditOptions& options, const RegisterDecoder& decoder, OutputStream& out) {
  AuditInput input(options);
  if (!input.plan()) return kExitBadInput;
  RunOutput output(output_settings(options), out);
  if (!output.open()) return kExitBadInput;
  Pipeline pipeline(input.pipeline_settings(pipeline_settings(options)), decoder, output.events());
  const bool complete = input.read(pipeline);
  output.end_of_input(input.end_time());
  AuditReport report = pipeline.report();
  input.complete(report);
  report.written_records = output.written_records();
  output.write_summary(report);
  out.flush();
  write_draft_maps(options, report);
  if (!output.close(report)) return kExitBadInput;
  if (!complete) {
    input.report_problems();
    return kExitBadInput;
  }
  return findings_status(options, report);
}

}  // namespace pvtap::analyzer
