#include "pvtap/statistics/timing_statistics.h"

#include "dialects/dialect_module.h"

#include <algorithm>

namespace pvtap {

namespace {

bool same_block(const FrameTiming& a, const FrameTiming& b) {
  return a.dialect == b.dialect && a.station == b.station && a.function == b.function &&
         a.start == b.start && a.count == b.count;
}

bool broadcast(const FrameTiming& f) {
  return f.station == 0 || detail::answered_broadcast(f.dialect, f.station);
}

}  // namespace

void TimingStatistics::add_frame(const FrameTiming& frame) {
  gaps_.add_frame(frame);
  if (frame.role == Role::Request && frame.check_ok) {
    std::optional<double> after_reply;
    if (previous_ && previous_->role == Role::Response)
      after_reply = frame.start_time - previous_->end_time;
    add_poll(frame, after_reply);
  }
  note_order(frame);
}

void TimingStatistics::add_frame_without_gaps(const FrameTiming& frame) {
  if (frame.role == Role::Request && frame.check_ok) add_poll(frame, std::nullopt);
  note_order(frame);
}

void TimingStatistics::add_echo(const FrameTiming& echo) {
  gaps_.extend_last(echo.end_time);
  if (previous_) previous_->end_time = std::max(previous_->end_time, echo.end_time);
}

void TimingStatistics::note_order(const FrameTiming& frame) {
  if (frame.role == Role::Request && frame.check_ok && previous_ &&
      previous_->role == Role::Request && previous_->check_ok && !broadcast(*previous_) &&
      !same_block(frame, *previous_) && latencies_ > 0 &&
      frame.start_time - previous_->end_time < usual_latency_ / 2)
    ++requests_while_reply_due_;
  previous_ = frame;
}

void TimingStatistics::add_poll(const FrameTiming& request, std::optional<double> after_reply) {
  const PollBlock block{request.dialect, request.station, request.function, request.start,
                        request.count};
  auto it = polls_.find(block);
  if (it == polls_.end()) {
    if (polls_.size() >= kMaxPollBlocks) {
      ++untracked_poll_requests_;
      return;
    }
    it = polls_.emplace(block, PollTrack{}).first;
  }
  PollTrack& track = it->second;
  if (track.requests > 0) track.cycle.add(request.start_time - track.last);
  track.last = request.start_time;
  track.series.add_event(request.start_time);
  ++track.requests;
  if (after_reply && *after_reply >= 0) track.turnaround.add(*after_reply);
}

void TimingStatistics::add_latency(std::optional<std::uint8_t> station, double seconds) {
  latency_.add(seconds);
  if (station) latency_by_station_[*station].add(seconds);
  ++latencies_;
  usual_latency_ +=
      (seconds - usual_latency_) / static_cast<double>(std::min<std::uint64_t>(latencies_, 64));
}

TimingReport TimingStatistics::report(const TimestampQuality& quality) const {
  TimingReport r;
  r.latency = latency_.summary();
  r.latency_by_station.reserve(latency_by_station_.size());
  for (const auto& [station, accumulator] : latency_by_station_) {
    r.latency_by_station.push_back(StationLatency{station, accumulator.summary()});
  }
  r.poll_periods.reserve(polls_.size());
  for (const auto& [block, track] : polls_) {
    r.poll_periods.push_back(PollPeriod{block, track.series.summary(), track.cycle.cycle(),
                                        track.cycle.mode(), track.requests, track.turnaround});
  }
  r.untracked_poll_requests = untracked_poll_requests_;
  r.bus = gaps_.report(quality);
  r.masters = recognise_masters(r.poll_periods);
  r.requests_while_reply_due = requests_while_reply_due_;
  return r;
}

}  // namespace pvtap
