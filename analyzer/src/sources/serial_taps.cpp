#include "sources/serial_taps.h"

#include <poll.h>

#include <algorithm>
#include <cstdio>

#include "pvtap/session/timestamping.h"
#include "serial/device_tap.h"
#include "sources/wall_clock.h"

namespace pvtap::analyzer {

struct SerialTaps::Tap {
  Tap(const std::string& path, std::uint32_t baud, SerialLine line, bool search)
      : device(path, baud, line, search) {}
  DeviceTap device;
  // A searched tap's bus is added once its search settles, with the rate it found.
  BusSession* bus = nullptr;
  // Who sends what this tap hears: one pair of a 4-wire bus, or Unknown (a 2-wire tap).
  Direction direction = Direction::Unknown;
  AutoBaud::BusBytes for_bus;  // what a searched tap's read gives the bus
  // The bus is known silent up to this moment: when the last read that found nothing began.
  // Not "now": bytes may have arrived since, unread while pvtap was scheduled out.
  double quiet_until = 0;
};

namespace {

constexpr std::size_t kReadBuffer = 64 * 1024;
// Reads per tap per wake-up, so that one flooding tap cannot starve the others.
constexpr int kReadsPerWake = 16;
// Line error counters are sampled this often, so that an unplug loses little of them.
constexpr double kLineErrorSampleEvery = 1.0;

}  // namespace

SerialTaps::SerialTaps(const LiveOptions& live, std::uint32_t baud, Pipeline& pipeline)
    : live_(live), baud_(baud), pipeline_(pipeline) {}

SerialTaps::~SerialTaps() = default;

BusSessionOptions SerialTaps::session_options(Tap& tap) const {
  BusSessionOptions o = pipeline_.bus_options(InputKind::Serial);
  o.reassembler.bits_per_char = live_.line.bits_per_char();
  if (AutoBaud* search = tap.device.search()) {
    o.reassembler.baud = search->baud();
    o.reassembler.bits_per_char = search->line().bits_per_char();
  }
  apply_timestamping({Timestamping::LiveSerial, 0.0, tap.device.latency_timer().ms}, o);
  return o;
}

bool SerialTaps::open() {
  for (const std::string& path : live_.devices) {
    taps_.push_back(std::make_unique<Tap>(path, baud_, live_.line, live_.search_line));
    Tap& tap = *taps_.back();
    if (!tap.device.open()) {
      std::fprintf(stderr, "pvtap: cannot open %s: %s\n", path.c_str(), tap.device.error().c_str());
      return false;
    }
    if (live_.duplex) tap.direction = taps_.size() == 1 ? Direction::ToSlave : Direction::FromSlave;
    if (!tap.device.search()) bus_of(tap);
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

BusSession& SerialTaps::bus_of(Tap& tap) {
  if (tap.bus) return *tap.bus;
  // Both pairs of a 4-wire bus are one bus, named by both devices, requests' first.
  if (live_.duplex && &tap != taps_.front().get()) {
    tap.bus = taps_.front()->bus;
    return *tap.bus;
  }
  // Named by its device also when it is the only one: the reader of a report or of jsonl
  // sees which tap heard it, and a --write file carries the name to a later audit.
  const std::string name = live_.duplex ? duplex_bus_name(live_) : tap.device.path();
  tap.bus = &pipeline_.add_bus(name, session_options(tap));
  return *tap.bus;
}

std::string duplex_bus_name(const LiveOptions& live) {
  std::string name;
  for (const std::string& device : live.devices) name += (name.empty() ? "" : "+") + device;
  return name;
}

void SerialTaps::add_found_lines(AuditReport& report) {
  for (const DeviceReport& d : report.live.devices) {
    if (!d.found_line) continue;
    for (BusFindings& bus : report.buses) {
      if (bus.name == d.path) bus.serial = d.found_line;
    }
  }
}

void SerialTaps::run(LiveLoop& loop, LiveSources& live) {
  loop_ = &loop;
  show_searches();
  std::vector<std::uint8_t> buffer(kReadBuffer);
  double now = wall_clock_seconds();
  next_sample_ = now + kLineErrorSampleEvery;
  while (!loop.should_stop()) {
    wait(next_wake(now));
    for (auto& tap : taps_) {
      if (tap->device.port().fd() >= 0) read(*tap, buffer);
    }
    now = wall_clock_seconds();
    after_wake(now);
    if (now >= next_sample_) {
      for (auto& tap : taps_) tap->device.sample_line_errors();
      if (loop.output().wants_line_errors()) report_line_errors(now);
      next_sample_ = now + kLineErrorSampleEvery;
    }
  }
  now = wall_clock_seconds();
  for (auto& tap : taps_) live.devices.push_back(tap->device.report(now));
  loop.end(now, live);
  loop_ = nullptr;
}

void SerialTaps::report_line_errors(double now) {
  if (live_.duplex) {
    report_duplex_line_errors(now);
    return;
  }
  for (auto& tap : taps_) {
    loop_->output().line_errors(tap->device.path(), tap->device.report(now).line_errors);
  }
}

// Both pairs' UARTs count for the one bus; not counted when either driver does not count.
void SerialTaps::report_duplex_line_errors(double now) {
  std::optional<LineErrorCounts> sum = LineErrorCounts{};
  for (auto& tap : taps_) {
    const std::optional<LineErrorCounts> e = tap->device.report(now).line_errors;
    if (!e || !sum) {
      sum.reset();
      continue;
    }
    *sum = *sum + *e;
  }
  loop_->output().line_errors(duplex_bus_name(live_), sum);
}

double SerialTaps::next_wake(double now) const {
  // The buses' own deadlines (the end of a t3.5 silence, a reply timeout) are in the loop's.
  double wake = std::min(loop_->wake_at(now), next_sample_);
  for (const auto& tap : taps_) {
    const DeviceOutage& outage = tap->device.outage();
    if (outage.ongoing()) wake = std::min(wake, outage.next_attempt());
  }
  return wake;
}

void SerialTaps::wait(double wake_at) {
  std::vector<pollfd> fds;
  for (const auto& tap : taps_) {
    const int fd = tap->device.port().fd();
    if (fd >= 0) fds.push_back(pollfd{fd, POLLIN, 0});
  }
  const timespec timeout = timeout_until(wake_at);
  // EINTR (a stop signal) just ends the wait; the loop then sees the request.
  ::ppoll(fds.data(), fds.size(), &timeout, nullptr);
}

void SerialTaps::read(Tap& tap, std::span<std::uint8_t> buffer) {
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
      lose(tap, time);
      return;
    }
    tap.device.count_read(got);
    if (tap.device.search()) {
      searched_read(tap, buffer.first(got), time);
    } else {
      tap.bus->feed(BusChunk{buffer.first(got), time, tap.direction});
    }
    // A read that did not fill the buffer emptied the driver's queue: no need for another
    // read (a system call per wake-up) to learn that nothing else was waiting.
    if (got < buffer.size()) return;
  }
}

void SerialTaps::searched_read(Tap& tap, std::span<const std::uint8_t> bytes, double time) {
  const AutoBaud::Outcome outcome = tap.device.search()->take(bytes, time, tap.for_bus);
  std::size_t from = 0;
  for (const auto& [end, read_time] : tap.for_bus.reads) {
    const auto piece = std::span<const std::uint8_t>(tap.for_bus.bytes).subspan(from, end - from);
    bus_of(tap).feed(BusChunk{piece, read_time, tap.direction});
    from = end;
  }
  after_search(tap, outcome, time);
}

void SerialTaps::after_search(Tap& tap, const AutoBaud::Outcome& outcome, double now) {
  if (!outcome.change && !outcome.settled) return;
  const AutoBaud& search = *tap.device.search();
  const char* path = tap.device.path().c_str();
  if (outcome.lost && tap.bus) tap.bus->data_lost(tap.direction, now, std::nullopt);
  if (!live_.quiet && (outcome.settled || outcome.lost)) loop_->make_room_on_stderr();
  if (!live_.quiet && outcome.settled) {
    std::fprintf(stderr, "pvtap: %s: %s found from the traffic\n", path,
                 search.setting_text().c_str());
  }
  if (!live_.quiet && outcome.lost) {
    std::fprintf(stderr, "pvtap: %s: the line stopped making sense; searching its rate again\n",
                 path);
  }
  if (outcome.change && !tap.device.follow_search()) {
    loop_->make_room_on_stderr();
    std::fprintf(stderr, "pvtap: %s: cannot set %s: %s\n", path, search.setting_text().c_str(),
                 tap.device.error().c_str());
  }
  show_searches();
}

void SerialTaps::show_searches() {
  std::string note;
  for (const auto& tap : taps_) {
    const AutoBaud* search = tap->device.search();
    if (!search) continue;
    if (!note.empty()) note += "; ";
    note += search->status_text();
  }
  loop_->set_status_note(note);
}

void SerialTaps::lose(Tap& tap, double now) {
  tap.device.went_away(now);
  if (tap.bus) tap.bus->data_lost(tap.direction, now, std::nullopt);
  loop_->make_room_on_stderr();
  std::fprintf(stderr, "pvtap: %s: device gone (%s); reopening it as it comes back\n",
               tap.device.path().c_str(), tap.device.error().c_str());
}

void SerialTaps::revive(double now) {
  for (auto& tap : taps_) {
    const DeviceOutage& outage = tap->device.outage();
    if (!outage.ongoing() || now < outage.next_attempt()) continue;
    const double since = outage.since();
    if (!tap->device.try_reopen(now)) continue;
    tap->quiet_until = now;
    loop_->make_room_on_stderr();
    std::fprintf(stderr, "pvtap: %s: back after %.1f s\n", tap->device.path().c_str(), now - since);
  }
}

void SerialTaps::after_wake(double now) {
  revive(now);
  for (auto& tap : taps_) {
    if (AutoBaud* search = tap->device.search()) after_search(*tap, search->tick(now), now);
  }
  // A bus is known silent up to where the last of its taps is; a tap that is gone has nothing
  // unread, so that its bus's timeouts run on the clock. Each bus once, by its first tap.
  for (auto it = taps_.begin(); it != taps_.end(); ++it) {
    BusSession* bus = (*it)->bus;
    const auto same_bus = [bus](const auto& tap) { return tap->bus == bus; };
    if (!bus || std::any_of(taps_.begin(), it, same_bus)) continue;
    double quiet = now;
    for (const auto& tap : taps_) {
      if (tap->bus == bus && tap->device.port().fd() >= 0)
        quiet = std::min(quiet, tap->quiet_until);
    }
    bus->idle(quiet);
  }
  loop_->after_wake(now);
}

}  // namespace pvtap::analyzer
