// The comparison behind `pvtap diff`: two audits of the same buses, before and after a change,
// in; the differences beyond the noise of sampling out, per bus and station. Pure: it reads
// two summaries and returns values.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "diff/register_ranges.h"
#include "report/audit_report.h"

namespace pvtap::analyzer {

// DiffSide: what one side's audit found, and the ranges its registers took.
struct DiffSide {
  AuditReport report;
  RegisterRangeMap ranges;
};

// DiffThresholds: how large a change must be to count. Rates are compared, not counts, so that
// captures of different lengths compare: bad checks per 1000 frames, timeouts and exceptions
// per 1000 requests, requests per minute. A rate differs when its change exceeds both the
// absolute and the relative threshold, and lies beyond `noise_sigmas` standard deviations of
// the Poisson noise of the two counts (the rate both sides share, at each side's size).
struct DiffThresholds {
  double noise_sigmas = 3;
  double rate_per_1000 = 1;      // bad checks, timeouts, exceptions, noise bytes
  double rate_percent = 50;      // of the before rate
  double requests_percent = 10;  // requests per minute
  double latency_ms = 10;        // p50 and p95
  double latency_percent = 25;
  double period_ms = 50;  // poll period
  double period_percent = 10;
  double jitter_ms = 100;
  double jitter_percent = 50;
  // A register moved when its after-range leaves its before-range by more than this share
  // of the before-range's size (or of its magnitude, where that is larger).
  double value_percent = 10;
  bool count_values = false;  // value moves count toward the exit status
  // Latency quantiles are compared only where each side measured at least this many.
  static constexpr std::uint64_t kMinLatencies = 10;
};

// Difference: one thing that changed. `counted`: it makes the exit status 1 (value moves
// only with count_values).
struct Difference {
  std::string bus;                      // the bus's name; "serial" for a serial capture's
  std::optional<std::uint8_t> station;  // none for what belongs to the bus
  std::string what;                     // a key: "bad_checks_per_1000_frames", "station", ...
  std::string detail;                   // the poll block or register, where there is one
  std::optional<double> before;         // none where the side has no such thing
  std::optional<double> after;
  std::string unit;    // of before and after: "per 1000 frames", "ms", "V", ...
  std::string reason;  // why it counts as a change, in words
  bool counted = true;
};

struct DiffResult {
  std::vector<Difference> differences;
  std::size_t counted() const;
};

// The differences of `after` against `before`. Buses pair by name; a side with one bus pairs
// it with the other side's one bus whatever their names.
DiffResult compare_sides(const DiffSide& before, const DiffSide& after,
                         const DiffThresholds& thresholds);

// Whether a count of k1 in n1 and one of k2 in n2 differ beyond `sigmas` standard deviations
// of the Poisson noise of their shared rate (k1 + k2) / (n1 + n2); false where n1 or n2 is 0.
bool beyond_poisson_noise(double k1, double n1, double k2, double n2, double sigmas);

}  // namespace pvtap::analyzer
