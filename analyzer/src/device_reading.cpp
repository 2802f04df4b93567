// AuditRun on serial taps (pvtap sniff --device): a poll loop over the taps that stamps each
// read with the capture clock, feeds one bus session per tap, tells the sessions when the bus
// has been silent, and survives adapters that go away and come back.
#include <poll.h>

#include <algorithm>
#include <cstdio>

#include "audit_bus.h"
#include "device_tap.h"
#include "pvtap/bus_timing.h"
#include "pvtap/carrier_timing.h"
#include "wall_clock.h"

namespace pvtap::analyzer {

struct AuditRun::LiveTap {
  LiveTap(const std::string& path, std::uint32_t baud, SerialLine line)
      : device(path, baud, line) {}
  DeviceTap device;
  BusSession* bus = nullptr;
  double t35 = 0;
  // The bus must be told of its silence t3.5 after the last byte (to decide a pending frame).
  std::optional<double> silence_due;
  // The bus is known silent up to this moment: when the last read that found nothing began.
  // Not "now": bytes may have arrived since, unread while pvtap was scheduled out.
  double quiet_until = 0;
};

namespace {

constexpr std::size_t kReadBuffer = 64 * 1024;
// Reads per tap per wake-up, so that one flooding tap cannot starve the others.
constexpr int kReadsPerWake = 16;
// The longest sleep: the matcher's timeouts and the status line are judged this often.
constexpr double kTick = 0.05;
// Line error counters are sampled this often, so that an unplug loses little of them.
constexpr double kLineErrorSampleEvery = 1.0;

}  // namespace

BusSessionOptions AuditRun::tap_session_options(LiveTap& tap) const {
  BusSessionOptions o = session_options(InputKind::Serial);
  o.reassembler.bits_per_char = options_.live.line.bits_per_char();
  const BusTiming timing(options_.baud, o.reassembler.bits_per_char);
  tap.t35 = timing.t35;
  apply_carrier_timing({Carrier::LiveSerial, 0.0, tap.device.latency_timer().ms}, o);
  return o;
}

bool AuditRun::open_taps(LiveTaps& taps) {
  const LiveOptions& live = options_.live;
  for (const std::string& path : live.devices) {
    taps.push_back(std::make_unique<LiveTap>(path, options_.baud, live.line));
    LiveTap& tap = *taps.back();
    if (!tap.device.open()) {
      std::fprintf(stderr, "pvtap: cannot open %s: %s\n", path.c_str(), tap.device.error().c_str());
      return false;
    }
    const std::string name = live.devices.size() > 1 ? path : "";
    tap.bus = &add_bus(name, tap_session_options(tap)).session;
    const LatencyTimerState& timer = tap.device.latency_timer();
    // Only a timer left coarse is worth a line on stderr (Wireshark shows an extcap's stderr
    // as an error); a lowered one is in the report.
    if (timer.ms && *timer.ms > 1) {
      std::fprintf(stderr, "pvtap: %s: USB latency timer %d ms (%s)\n", path.c_str(), *timer.ms,
                   timer.note.c_str());
    }
  }
  return true;
}

bool AuditRun::read_devices() {
  LiveTaps taps;
  if (!open_taps(taps)) return false;
  status_ = std::make_unique<StatusLine>(options_.live.status_line);
  std::vector<std::uint8_t> buffer(kReadBuffer);
  const double started = wall_clock_seconds();
  double now = started;
  double next_sample = started + kLineErrorSampleEvery;
  while (!live_should_stop(started)) {
    wait_for_taps(taps, next_wake(taps, now, started));
    for (auto& tap : taps) {
      if (tap->device.fd() >= 0) read_tap(*tap, buffer);
    }
    now = wall_clock_seconds();
    after_wake(taps, now);
    if (now >= next_sample) {
      for (auto& tap : taps) tap->device.sample_line_errors();
      next_sample = now + kLineErrorSampleEvery;
    }
  }
  now = wall_clock_seconds();
  for (auto& tap : taps) live_.devices.push_back(tap->device.report(now));
  end_live_capture(started, now);
  return true;
}

double AuditRun::next_wake(const LiveTaps& taps, double now, double started) const {
  double wake = now + kTick;
  for (const auto& tap : taps) {
    if (tap->silence_due) wake = std::min(wake, *tap->silence_due);
    if (tap->device.gone()) wake = std::min(wake, tap->device.next_attempt());
  }
  if (options_.live.duration > 0) wake = std::min(wake, started + options_.live.duration);
  return wake;
}

void AuditRun::wait_for_taps(LiveTaps& taps, double wake_at) {
  std::vector<pollfd> fds;
  for (const auto& tap : taps) {
    if (tap->device.fd() >= 0) fds.push_back(pollfd{tap->device.fd(), POLLIN, 0});
  }
  const timespec timeout = timeout_until(wake_at);
  // EINTR (a stop signal) just ends the wait; the loop then sees the request.
  ::ppoll(fds.data(), fds.size(), &timeout, nullptr);
}

void AuditRun::read_tap(LiveTap& tap, std::span<std::uint8_t> buffer) {
  for (int k = 0; k < kReadsPerWake; ++k) {
    std::size_t got = 0;
    const double before = wall_clock_seconds();
    const SerialPort::ReadResult result = tap.device.port().read(buffer, got);
    // The capture clock right after the read: the time of the chunk's last byte.
    const double time = wall_clock_seconds();
    if (result == SerialPort::ReadResult::Empty) {
      tap.quiet_until = before;
      return;
    }
    if (result == SerialPort::ReadResult::Gone) {
      lose_tap(tap, time);
      return;
    }
    tap.device.count_read(got);
    tap.bus->feed(BusChunk{buffer.first(got), time, Direction::Unknown});
    tap.silence_due = time + tap.t35;
    // A read that did not fill the buffer emptied the driver's queue: no need for another
    // read (a system call per wake-up) to learn that nothing else was waiting.
    if (got < buffer.size()) return;
  }
}

void AuditRun::lose_tap(LiveTap& tap, double now) {
  tap.device.went_away(now);
  tap.silence_due.reset();
  tap.bus->data_lost(Direction::Unknown, now, std::nullopt);
  status_->clear();
  std::fprintf(stderr, "pvtap: %s: device gone (%s); reopening it as it comes back\n",
               tap.device.path().c_str(), tap.device.error().c_str());
}

void AuditRun::revive_taps(LiveTaps& taps, double now) {
  for (auto& tap : taps) {
    if (!tap->device.gone() || now < tap->device.next_attempt()) continue;
    const double since = tap->device.outage_started();
    if (!tap->device.try_reopen(now)) continue;
    tap->quiet_until = now;
    status_->clear();
    std::fprintf(stderr, "pvtap: %s: back after %.1f s\n", tap->device.path().c_str(), now - since);
  }
}

void AuditRun::after_wake(LiveTaps& taps, double now) {
  revive_taps(taps, now);
  for (auto& tap : taps) {
    if (tap->silence_due && tap->quiet_until >= *tap->silence_due) tap->silence_due.reset();
    // A tap that is gone has nothing unread: its timeouts run on the clock.
    tap->bus->idle(tap->device.fd() >= 0 ? tap->quiet_until : now);
  }
  flush_live_output(now);
}

}  // namespace pvtap::analyzer
