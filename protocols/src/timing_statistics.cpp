#include "pvtap/timing_statistics.h"

namespace pvtap {

void TimingStatistics::add_frame(const FrameTiming& frame) {
  gaps_.add_frame(frame);
  if (frame.role == Role::Request) {
    polls_[PollKey{frame.dialect, frame.station, frame.function}].add_event(frame.start_time);
  }
}

void TimingStatistics::add_latency(std::uint8_t station, double seconds) {
  latency_.add(seconds);
  latency_by_station_[station].add(seconds);
}

TimingReport TimingStatistics::report(const TimestampQuality& quality) const {
  TimingReport r;
  r.latency = latency_.summary();
  r.latency_by_station.reserve(latency_by_station_.size());
  for (const auto& [station, accumulator] : latency_by_station_) {
    r.latency_by_station.push_back(StationLatency{station, accumulator.summary()});
  }
  r.poll_periods.reserve(polls_.size());
  for (const auto& [key, series] : polls_) {
    const auto& [dialect, station, function] = key;
    r.poll_periods.push_back(PollPeriod{dialect, station, function, series.summary()});
  }
  r.bus = gaps_.report(quality);
  return r;
}

}  // namespace pvtap
