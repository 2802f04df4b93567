// AuditReport: everything one `pvtap audit` run found, for the summary writers.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "pvtap/registers/register_decoder.h"
#include "pvtap/session/bus_report.h"
#include "pvtap/statistics/distribution_summary.h"
#include "report/live_report.h"
#include "report/network_stats.h"
#include "report/serial_line_report.h"

namespace pvtap::analyzer {

// InputReport: how reading one file went.
struct InputReport {
  std::string path;
  std::string link_type;      // "EN10MB (Ethernet)", or "raw bytes"
  std::uint64_t records = 0;  // packets (or read chunks of a raw dump)
  std::uint64_t file_bytes = 0;
  std::uint64_t read_bytes = 0;  // how far reading got
  bool truncated = false;        // the file ended inside a record: what came before is read
  bool unreadable = false;       // not read at all (missing, not a capture): `error` says why
  std::string error;             // why reading stopped early, or never began
  // The first and the last record's time, as read (after the steps back below).
  std::optional<double> first_time;
  double last_time = 0;
  // The file's clock went back between two records: each step back is a finding, and the
  // records after it are moved on by the step, so that no time and no latency runs backwards.
  std::uint64_t steps_back = 0;
  std::uint64_t first_step_back_record = 0;  // 1-based, in the file
  double largest_step_back = 0;              // seconds

  // Read in part or not at all: the exit status says so.
  bool damaged() const { return truncated || unreadable; }
};

// BusFindings: one bus and its report.
struct BusFindings {
  std::string name;  // the gateway's endpoint; empty for the one bus of a serial capture
  BusReport report;
  // A bus decoded from a logic analyzer's samples: its serial line.
  std::optional<SerialLineReport> serial;
};

// SkippedRecords: records that carried no bus bytes, by reason.
struct SkippedRecords {
  std::uint64_t not_ip = 0;
  std::uint64_t other_ip = 0;
  std::uint64_t fragments = 0;
  std::uint64_t malformed = 0;
  std::uint64_t foreign_pdus = 0;  // link type 252 records for other dissectors
};

// AuditSettings: the options that shape the report's wording.
struct AuditSettings {
  std::uint32_t baud = 9600;
  double timeout = 1.0;
  bool has_timestamps = true;
  GslIdReading gsl_ids = GslIdReading::Decimal;  // to write GSL addresses as the reference does
  bool all_dialects = true;  // --dialect auto: for what to try when no frame was found
  bool ports_given = false;  // --port
};

// TimeSpan: from the first to the last byte of the input.
struct TimeSpan {
  double first = 0;
  double last = 0;
  double seconds() const { return last - first; }
};

struct AuditReport {
  AuditSettings settings;
  std::vector<InputReport> inputs;
  std::vector<BusFindings> buses;
  bool network = false;  // gateway traffic was read
  NetworkStats flows;
  SkippedRecords skipped;
  DistributionSummary latency;  // over every bus
  std::uint64_t written_records = 0;
  LiveSources live;  // pvtap sniff only

  // Sums over all buses.
  BusReport totals() const;
  // The time the buses' bytes span; nullopt without timestamps or bytes.
  std::optional<TimeSpan> time_span() const;
};

// Bad checks, timeouts or exceptions were found (--fail-on errors).
bool has_findings(const AuditReport& report);
// No frame was found at all (--fail-on empty, and --fail-on errors).
bool found_no_frame(const AuditReport& report);
// Why an audit may have found no frame, and what to try: empty when frames were found.
std::string no_frame_hint(const AuditReport& report);

}  // namespace pvtap::analyzer
