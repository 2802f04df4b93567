#include "sources/interface_source.h"

#include <poll.h>

#include <algorithm>
#include <cstdio>

#include "sources/wall_clock.h"

namespace pvtap::analyzer {
namespace {

// Packets taken per wake-up, so that a flood cannot hold off the stop checks and timeouts.
constexpr int kPacketsPerWake = 256;
constexpr int kDrainDispatches = 64;

// Waits until a packet may be there, `wake_at` comes or a stop signal interrupts.
void wait_for_packets(int fd, double wake_at) {
  const timespec timeout = timeout_until(wake_at);
  pollfd waiting{fd, POLLIN, 0};
  // Without a selectable descriptor the tick alone paces the reads.
  ::ppoll(fd >= 0 ? &waiting : nullptr, fd >= 0 ? 1 : 0, &timeout, nullptr);
}

InterfaceReport interface_report(const LiveCapture& capture, const std::string& name) {
  InterfaceReport r;
  r.name = name;
  r.filter = capture.setup().filter;
  r.link_type = capture.setup().link_type_name();
  r.packets = capture.packets();
  const LiveDrops drops = capture.drops();
  r.dropped = drops.kernel;
  r.interface_dropped = drops.interface;
  return r;
}

// Opens the capture and says so on stderr; once the line is there every packet is seen
// (scripts wait for it, as they do for tcpdump's "listening on").
bool open_capture(LiveCapture& capture, const LiveOptions& live,
                  const std::vector<std::uint16_t>& ports) {
  const std::string& name = live.interface;
  if (!capture.open(LiveCaptureSettings{name, ports, live.filter})) {
    std::fprintf(stderr, "pvtap: cannot capture on %s: %s\n", name.c_str(),
                 capture.error().c_str());
    return false;
  }
  for (const std::string& warning : capture.setup().warnings) {
    std::fprintf(stderr, "pvtap: %s: %s\n", name.c_str(), warning.c_str());
  }
  std::fprintf(stderr, "pvtap: capturing on %s, link type %s, filter \"%s\"\n", name.c_str(),
               capture.setup().link_type_name().c_str(), capture.setup().filter.c_str());
  return true;
}

// Takes the packets the kernel captured before the stop, so that a stop loses none of them;
// bounded, so that a flood cannot hold the stop off.
void drain(LiveCapture& capture, const LiveCapture::PacketHandler& handler) {
  for (int k = 0; k < kDrainDispatches; ++k) {
    if (capture.dispatch(kPacketsPerWake, handler) <= 0) return;
  }
}

}  // namespace

InterfaceSource::InterfaceSource(const LiveOptions& live, const std::vector<std::uint16_t>& ports,
                                 Pipeline& pipeline)
    : live_(live), ports_(ports), pipeline_(pipeline) {}

bool InterfaceSource::open() {
  if (!open_capture(capture_, live_, ports_)) return false;
  // Records are decoded by the link type, as those of a capture file.
  pipeline_.begin_input(capture_.setup().link_type, false);
  return true;
}

void InterfaceSource::run(LiveLoop& loop, LiveSources& live) {
  const std::string& name = live_.interface;
  const auto handler = [this, &loop](const CapturedPacket& packet) {
    loop.saw_time(packet.time);
    pipeline_.record(packet);
  };
  while (!loop.should_stop()) {
    wait_for_packets(capture_.selectable_fd(), loop.wake_at(wall_clock_seconds()));
    // Read before the packets are taken: a reply captured after it cannot be late for it.
    const double now = wall_clock_seconds();
    const int taken = capture_.dispatch(kPacketsPerWake, handler);
    if (taken < 0) {
      loop.make_room_on_stderr();
      std::fprintf(stderr, "pvtap: %s: capture stopped: %s\n", name.c_str(),
                   capture_.error().c_str());
      break;
    }
    // A full batch leaves packets waiting: the buses may only know the time up to the last
    // one taken, or a reply still waiting would count as missing.
    pipeline_.idle(taken < kPacketsPerWake ? now : loop.last_time());
    loop.after_wake(now);
  }
  // --count stops at a frame: what came after it stays out.
  if (!loop.count_reached()) drain(capture_, handler);
  live.interface = interface_report(capture_, name);
  loop.end(wall_clock_seconds(), live);
}

}  // namespace pvtap::analyzer
