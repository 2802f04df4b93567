// Latency, poll-period and bus-gap statistics of a whole capture.
#pragma once

#include <compare>
#include <cstdint>
#include <map>
#include <optional>
#include <vector>

#include "pvtap/statistics/bus_gap_statistics.h"
#include "pvtap/statistics/bus_timing.h"
#include "pvtap/statistics/distribution_summary.h"
#include "pvtap/statistics/frame_timing.h"
#include "pvtap/statistics/interval_series.h"
#include "pvtap/statistics/poll_masters.h"

namespace pvtap {

// StationLatency: reply latencies of one answering station.
struct StationLatency {
  std::uint8_t station = 0;
  DistributionSummary latency;
};

// PollBlock: what one request asks of one station: its function and the registers it names.
// A master that reads four blocks of a station every 5 s polls four blocks, each every 5 s.
// start and count are the request's own fields, absent where the request has none: a read or
// a block write has both, a one-register write (GSL 0x06, Hybrid 0x18) a start only, a frame
// of an unknown function neither. Absent is not 0: a read of 0 registers at 0 is its own block.
struct PollBlock {
  Dialect dialect = kDefaultDialect;
  std::uint8_t station = 0;  // 0xFF for Hybrid broadcasts
  std::uint8_t function = 0;
  std::optional<std::uint16_t> start;  // wire address
  std::optional<std::uint16_t> count;
  friend auto operator<=>(const PollBlock&, const PollBlock&) = default;
};

// PollPeriod: how regularly the master sends one poll block, from the start times of its
// requests. period.mean is the period; the jitter is period.stddev, the population standard
// deviation of the intervals; period.max_deviation is the largest |interval - period|. A block
// requested once has no interval: intervals is 0 and every figure 0 (not measured, the JSON
// summary writes null). With one interval the jitter and the maximum deviation are 0.
// cycle is the block's most frequent interval (ModalInterval), which names its master;
// turnaround the times from a reply's end to this block's request, measured where the frame
// before the request was a reply and the timestamps are fine.
struct PollPeriod {
  PollBlock block;
  IntervalSummary period;
  std::optional<double> cycle;
  std::optional<double> mode;  // its most frequent interval, regular or not
  std::uint64_t requests = 0;
  CoarseMedian turnaround;
};

// TimingReport: everything TimingStatistics measured, ready to print as text or JSON.
// Latency quantiles are within latency_relative_error of the nearest-rank quantile of the
// exact values; count, min, max and mean are exact. Stations and poll blocks are sorted
// (dialect, station, function, start, count; an absent start or count first).
struct TimingReport {
  double latency_relative_error = LogHistogram::kRelativeError;
  DistributionSummary latency;
  std::vector<StationLatency> latency_by_station;
  std::vector<PollPeriod> poll_periods;
  // Requests of blocks first seen once TimingStatistics::kMaxPollBlocks were tracked: they are
  // in no poll period.
  std::uint64_t untracked_poll_requests = 0;
  BusGapReport bus;
  // The masters told apart by their cycles (recognise_masters), busiest first.
  std::vector<MasterPlan> masters;
  // Good requests sent less than half the usual latency after another good request that no
  // reply followed: its reply was still due, which one master never does (another master
  // spoke). Broadcasts and a request repeated at once (an echo) are not counted.
  std::uint64_t requests_while_reply_due = 0;
};

// TimingStatistics: accumulates a capture's timing in memory bounded by the number of
// stations and of poll blocks, at most kMaxPollBlocks (not by its length).
//
// Feed every frame in bus order with add_frame (requests drive the poll periods; give the
// role as the TransactionMatcher returned it, so that GSL 0x06 echoes are not counted as
// polls) and every Transaction's latency with add_latency. A request with a bad check is in
// no poll period: any of its station, function, start and count may be the damaged byte, so
// its block is unknown (the real block shows one longer interval). Negative latencies
// (possible with coarse clocks) count in min and mean as they are and fall in the histogram's
// lowest bucket.
class TimingStatistics {
 public:
  // A master polls tens of blocks; thousands means damaged or scanning traffic.
  static constexpr std::size_t kMaxPollBlocks = 4096;

  explicit TimingStatistics(BusTiming timing) : gaps_(timing) {}

  void add_frame(const FrameTiming& frame);
  // A frame of a bus whose silences are never judged (timestamps declared too coarse: a
  // gateway's segments): a request's poll period and the order of requests and replies are
  // kept, the gap statistics are spared.
  void add_frame_without_gaps(const FrameTiming& frame);
  // A request's echo (the tap's adapter repeating it): the line was busy until its end, but it
  // is neither a poll nor a gap of the bus's own.
  void add_echo(const FrameTiming& echo);
  // A latency of no station (both frames of its transaction damaged) is in the bus's alone.
  void add_latency(std::optional<std::uint8_t> station, double seconds);
  TimingReport report(const TimestampQuality& quality) const;
  // So far (TimingReport::requests_while_reply_due), for a session watching for a second master.
  std::uint64_t requests_while_reply_due() const { return requests_while_reply_due_; }

 private:
  struct PollTrack {
    IntervalSeries series;
    ModalInterval cycle;
    double last = 0;  // the start of its latest request
    std::uint64_t requests = 0;
    CoarseMedian turnaround;
  };
  // `after_reply`: the frame before it was a reply that ended this long before it began.
  void add_poll(const FrameTiming& request, std::optional<double> after_reply);
  void note_order(const FrameTiming& frame);

  DistributionAccumulator latency_;
  std::map<std::uint8_t, DistributionAccumulator> latency_by_station_;
  std::map<PollBlock, PollTrack> polls_;
  // The frame before (for turnarounds and requests sent while a reply was due), and a running
  // mean of the latencies so far.
  std::optional<FrameTiming> previous_;
  double usual_latency_ = 0;
  std::uint64_t latencies_ = 0;
  std::uint64_t requests_while_reply_due_ = 0;
  std::uint64_t untracked_poll_requests_ = 0;
  BusGapStatistics gaps_;
};

}  // namespace pvtap
