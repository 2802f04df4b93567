// AuditOptions: what `pvtap audit` was asked to do, as parsed from its command line.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "event_writer.h"
#include "pvtap/dialect.h"
#include "pvtap/register_decoder.h"

namespace pvtap::analyzer {

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
  std::vector<std::uint16_t> ports;
  GslIdReading gsl_ids = GslIdReading::Decimal;
  std::vector<std::string> maps;
  OutputFormat format = OutputFormat::Text;
  bool summary_only = false;
  std::string write_path;
  bool fail_on_errors = false;
  bool progress = false;  // draw a progress bar on stderr
};

}  // namespace pvtap::analyzer
