#include "pvtap/statistics/timing_statistics.h"

namespace pvtap {

void TimingStatistics::add_frame(const FrameTiming& frame) {
  gaps_.add_frame(frame);
  if (frame.role == Role::Request && frame.check_ok) add_poll(frame);
}

void TimingStatistics::add_frame_without_gaps(const FrameTiming& frame) {
  if (frame.role == Role::Request && frame.check_ok) add_poll(frame);
}

void TimingStatistics::add_poll(const FrameTiming& request) {
  const PollBlock block{request.dialect, request.station, request.function, request.start,
                        request.count};
  auto it = polls_.find(block);
  if (it == polls_.end()) {
    if (polls_.size() >= kMaxPollBlocks) {
      ++untracked_poll_requests_;
      return;
    }
    it = polls_.emplace(block, IntervalSeries{}).first;
  }
  it->second.add_event(request.start_time);
}

void TimingStatistics::add_latency(std::optional<std::uint8_t> station, double seconds) {
  latency_.add(seconds);
  if (station) latency_by_station_[*station].add(seconds);
}

TimingReport TimingStatistics::report(const TimestampQuality& quality) const {
  TimingReport r;
  r.latency = latency_.summary();
  r.latency_by_station.reserve(latency_by_station_.size());
  for (const auto& [station, accumulator] : latency_by_station_) {
    r.latency_by_station.push_back(StationLatency{station, accumulator.summary()});
  }
  r.poll_periods.reserve(polls_.size());
  for (const auto& [block, series] : polls_) {
    r.poll_periods.push_back(PollPeriod{block, series.summary()});
  }
  r.untracked_poll_requests = untracked_poll_requests_;
  r.bus = gaps_.report(quality);
  return r;
}

}  // namespace pvtap
