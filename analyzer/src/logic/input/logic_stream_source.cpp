// LogicStreamSource: a probe over the held first stretch, then the UART tap over the rest.
#include "logic/input/logic_stream_source.h"

#include <fcntl.h>
#include <poll.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string>

#include "logic/logic_run.h"
#include "sources/wall_clock.h"

namespace pvtap::analyzer {
namespace {

constexpr std::size_t kReadSize = 1 << 20;
constexpr double kLongestWait = 0.2;  // seconds

std::vector<LogicChannel> named_channels(const std::vector<std::string>& names) {
  std::vector<LogicChannel> channels;
  for (unsigned k = 0; k < names.size(); ++k) channels.push_back(LogicChannel{names[k], k});
  return channels;
}

}  // namespace

LogicStreamSource::LogicStreamSource(const LiveOptions& live, Pipeline& pipeline)
    : live_(live), pipeline_(pipeline) {}

LogicStreamSource::~LogicStreamSource() {
  if (fd_ > STDIN_FILENO) ::close(fd_);
}

bool LogicStreamSource::read_chunk() {
  chunk_.assign(partial_.begin(), partial_.end());
  partial_.clear();
  const std::size_t had = chunk_.size();
  chunk_.resize(had + kReadSize);
  ssize_t n = -1;
  do {
    n = ::read(fd_, chunk_.data() + had, kReadSize);
  } while (n < 0 && errno == EINTR && !ended_);
  if (n <= 0) {
    chunk_.resize(had - had % unitsize_);
    ended_ = true;
    return false;
  }
  const std::size_t total = had + static_cast<std::size_t>(n);
  const std::size_t whole = total - total % unitsize_;
  partial_.assign(chunk_.begin() + static_cast<std::ptrdiff_t>(whole),
                  chunk_.begin() + static_cast<std::ptrdiff_t>(total));
  chunk_.resize(whole);
  return true;
}

bool LogicStreamSource::open() {
  const std::string& path = live_.logic_input;
  fd_ = path == "-" ? STDIN_FILENO : ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd_ < 0) {
    std::fprintf(stderr, "pvtap: cannot open %s: %s\n", path.c_str(), std::strerror(errno));
    return false;
  }
  unitsize_ = static_cast<unsigned>((live_.logic_channels.size() + 7) / 8);
  LineProbe probe({});
  probe.begin(named_channels(live_.logic_channels), live_.sample_rate);
  while (probe.wants_more() && held_.size() < kHoldLimit) {
    const bool more = read_chunk();
    probe.samples(chunk_, unitsize_);
    held_.insert(held_.end(), chunk_.begin(), chunk_.end());
    if (!more) break;
  }
  probe.finish();
  plan_.path = path == "-" ? "standard input" : path;
  plan_.sample_rate = live_.sample_rate;
  keep_probed(probe, false, plan_);
  if (!plan_.error.empty()) {
    std::fprintf(stderr, "pvtap: %s\n", plan_.error.c_str());
    return false;
  }
  return true;
}

void LogicStreamSource::run(LiveLoop& loop, LiveSources& live) {
  loop.use_sample_clock();
  tap_ = tap_planned_channels(plan_, pipeline_);
  tap_->samples(held_, unitsize_);
  held_ = {};
  loop.saw_time(tap_->end_time());
  while (!ended_ && !loop.should_stop()) {
    pollfd fd{fd_, POLLIN, 0};
    // The buses' deadlines are on the sample clock: only the stream moves it, so the wait is
    // for samples, and short enough for --duration and the status line.
    const timespec timeout = timeout_until(wall_clock_seconds() + kLongestWait);
    // EINTR (a stop signal) just ends the wait; the loop then sees the request.
    if (::ppoll(&fd, 1, &timeout, nullptr) > 0) {
      read_chunk();
      tap_->samples(chunk_, unitsize_);
      loop.saw_time(tap_->end_time());
    }
    loop.after_wake(wall_clock_seconds());
  }
  tap_->finish();
  loop.saw_time(tap_->end_time());
  lines_ = tap_->lines();
  loop.end(wall_clock_seconds(), live);
}

void LogicStreamSource::add_found_lines(AuditReport& report) const {
  LogicRun run;
  run.lines = lines_;
  run.input.path = plan_.path;
  run.input.link_type = logic_link_text(plan_);
  run.input.records = tap_ ? tap_->chunks() : 0;
  add_serial_lines(run, report);
}

}  // namespace pvtap::analyzer
