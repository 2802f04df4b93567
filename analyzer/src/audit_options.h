// AuditOptions: what `pvtap audit` was asked to do, as parsed from its command line.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "event_writer.h"
#include "mqtt/mqtt_options.h"
#include "pvtap/dialect.h"
#include "pvtap/register_decoder.h"

namespace pvtap::analyzer {

// SerialLine: the character format of a tapped RS485 line besides its baud rate (the tap
// must match the bus, or characters read as framing or parity errors).
struct SerialLine {
  char parity = 'N';  // 'N', 'E' or 'O'
  int stop_bits = 1;
  // Bits on the wire per character: start, 8 data, parity, stop.
  unsigned bits_per_char() const {
    return 9u + (parity == 'N' ? 0u : 1u) + static_cast<unsigned>(stop_bits);
  }
  // The letter for a parity as the command line and Wireshark's dialog name it: "none",
  // "even" or "odd".
  static char parity_letter(std::string_view name) {
    if (name == "even") return 'E';
    if (name == "odd") return 'O';
    return 'N';
  }
};

// LiveOptions: what `pvtap sniff` reads instead of files, and when it stops.
struct LiveOptions {
  std::vector<std::string> devices;  // serial devices (RS485 taps), each its own bus
  SerialLine line;
  std::string interface;     // a network interface with a gateway's TCP traffic (libpcap)
  std::string filter;        // BPF filter for the interface, added to the --port filter
  double duration = 0;       // seconds; 0 runs until SIGINT/SIGTERM
  std::uint64_t count = 0;   // frames; 0 means no limit
  bool status_line = false;  // a live status line on stderr
  bool quiet = false;        // nothing on stdout (extcap: the frames go to the fifo)
  // Each record written to --write is flushed at once, so an abrupt end loses nothing.
  bool flush_each_record = false;
  bool active() const { return !devices.empty() || !interface.empty(); }
};

struct AuditOptions {
  std::vector<std::string> captures;   // pcap/pcapng files, read in order as one capture
  std::vector<std::string> raw_dumps;  // plain bus byte dumps (--raw)
  // As typed; apply_choices() turns them into the typed fields below.
  std::string dialect = "auto";  // auto, ascii, hybrid or gsl
  std::string gsl_id_reading = "decimal";
  std::string format_name = "text";
  std::string fail_on;  // empty or "errors"

  DialectSet dialects = DialectSet::all();
  std::uint32_t baud = 9600;
  double timeout = 1.0;  // seconds
  // A silence this long between two TCP/UDP segments of one direction proves a frame
  // boundary (see ReassemblerOptions::boundary_gap); 0 never.
  double gateway_gap_ms = 50;
  std::vector<std::uint16_t> ports;
  GslIdReading gsl_ids = GslIdReading::Decimal;
  std::vector<std::string> maps;
  OutputFormat format = OutputFormat::Text;
  bool summary_only = false;
  std::string write_path;
  bool fail_on_errors = false;
  bool progress = false;  // draw a progress bar on stderr
  LiveOptions live;       // pvtap sniff: live sources instead of the files above
  MqttOptions mqtt;       // --mqtt: also publish to a broker
};

}  // namespace pvtap::analyzer
