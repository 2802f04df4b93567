// What `pvtap audit` and `pvtap sniff` were asked to do, as parsed from their command lines.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "mqtt/mqtt_options.h"
#include "pipeline/protocol_choices.h"
#include "pvtap/codec/dialect.h"
#include "pvtap/registers/register_decoder.h"
#include "sources/live_options.h"
#include "writers/event_writers.h"
#include "writers/values_writer.h"

namespace pvtap::analyzer {

// CommonOptions: the protocol, register map and output options both commands take.
struct CommonOptions {
  // As typed; apply_choices() turns them into the typed fields below.
  std::string dialect = "auto";  // auto, ascii, hybrid or gsl
  std::string gsl_id_reading = "decimal";
  std::string format_name = "text";
  std::string fail_on;  // empty, "errors" or "empty"

  DialectSet dialects = DialectSet::all();
  std::uint32_t baud = 9600;
  double timeout = 1.0;  // seconds
  // Which of --dialect, --baud and --timeout the command line gave: a capture pvtap wrote
  // brings its run's settings, and only these override them.
  ProtocolChoices given;
  // A silence this long between two TCP/UDP segments of one direction proves a frame
  // boundary (see ReassemblerOptions::boundary_gap); 0 never.
  double gateway_gap_ms = 50;
  std::vector<std::uint16_t> ports;
  GslIdReading gsl_ids = GslIdReading::Decimal;
  bool no_sunspec = false;  // SunSpec devices' words stay unmapped
  std::vector<std::string> maps;
  OutputFormat format = OutputFormat::Text;
  bool summary_only = false;
  std::string write_path;
  bool fail_on_errors = false;
  bool fail_on_empty = false;  // --fail-on empty, and errors
  // --values: the decoded register values as a time series, one row per value.
  std::string values_path;
  std::string values_format_name = "csv";
  ValuesFormat values_format = ValuesFormat::Csv;
  // --html: the report as one self-contained page; --plot narrows its value charts.
  std::string html_path;
  std::vector<std::string> plot_keys;
  MqttOptions mqtt;  // --mqtt: also publish to a broker
};

// AuditOptions: `pvtap audit`: capture files or plain dumps.
struct AuditOptions : CommonOptions {
  std::vector<std::string> captures;   // pcap/pcapng files, read in order as one capture
  std::vector<std::string> raw_dumps;  // plain bus byte dumps (--raw)
  // --draft-map: a folder for station-N.toml, a draft map of each station with unmapped words.
  std::string draft_map_dir;
  // --channels: a logic recording's channels to decode, by name; empty for every channel
  // with UART traffic.
  std::vector<std::string> logic_channels;
  // --de: driver-enable channels of a logic recording, for the drivers' turnaround.
  std::vector<std::string> logic_drivers;
  // --samplerate: a logic recording's sample rate where the file gives none (a CSV export),
  // or in place of the one it gives; as written ("4M").
  std::string logic_sample_rate;
  bool progress = false;  // draw a progress bar on stderr
  // --threads: 2 reads capture files ahead on a second thread, 1 reads and analyses on one;
  // 0 (the default) picks 2 when this process may run on more than one CPU.
  unsigned threads = 0;
  // --duplex: the two FILEs are the two pairs of a 4-wire bus, the requests' first.
  bool duplex = false;
};

// SniffOptions: `pvtap sniff` (and the extcap capture): live sources.
struct SniffOptions : CommonOptions {
  LiveOptions live;
};

}  // namespace pvtap::analyzer
