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
  // --duplex: which pair of the 4-wire bus the file holds, "requests" or "replies"; empty
  // on a 2-wire bus.
  std::string pair;
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

// Where the input's times count from: the wall clock (epoch seconds, written as UTC), or the
// start of a recording that has no wall-clock time (a logic analyzer's samples, timed by its
// sample clock), whose times must never be written as dates.
enum class TimeBase { WallClock, RecordingStart };

// AuditSettings: the options that shape the report's wording.
struct AuditSettings {
  std::uint32_t baud = 9600;
  double timeout = 1.0;
  bool has_timestamps = true;
  TimeBase time_base = TimeBase::WallClock;
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

// A moment as the report writes it: the UTC time of day ("10:00:00.012345"), or the seconds
// from the recording's start ("+12.345678 s"); nothing without timestamps.
void append_report_time(std::string& out, const AuditSettings& settings, double time);
// The span of the input's times, as the text and the HTML report write it:
// "2024-05-01 10:00:00.000000 .. 2024-05-01 10:05:00.000000 UTC (300.0 s)", or
// "+0.000000 s .. +12.345678 s from the recording's start (no wall-clock time; 12.3 s)";
// empty without a span.
std::string time_span_text(const AuditReport& report);

// Bad checks, timeouts or exceptions were found (--fail-on errors).
bool has_findings(const AuditReport& report);
// No frame was found at all (--fail-on empty, and --fail-on errors).
bool found_no_frame(const AuditReport& report);
// Why an audit may have found no frame, and what to try: empty when frames were found.
std::string no_frame_hint(const AuditReport& report);

}  // namespace pvtap::analyzer
