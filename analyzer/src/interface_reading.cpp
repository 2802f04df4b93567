// AuditRun on a network interface (pvtap sniff --interface): libpcap hands over a gateway's
// packets as they cross, and they go down the same pipeline as the records of a capture file.
// A poll loop with a short tick tells the bus sessions the time, so that timeouts are judged
// while the capture runs and not only when the next packet comes.
#include <poll.h>

#include <algorithm>
#include <cstdio>

#include "audit_bus.h"
#include "live_capture.h"
#include "wall_clock.h"

namespace pvtap::analyzer {
namespace {

// The longest sleep: the matcher's timeouts and the status line are judged this often.
constexpr double kTick = 0.05;
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
  r.filter = capture.filter();
  r.link_type = capture.link_type_name();
  r.packets = capture.packets();
  const LiveDrops drops = capture.drops();
  r.dropped = drops.kernel;
  r.interface_dropped = drops.interface;
  return r;
}

// Opens the capture and says so on stderr; once the line is there every packet is seen
// (scripts wait for it, as they do for tcpdump's "listening on").
bool open_capture(LiveCapture& capture, const AuditOptions& o) {
  const std::string& name = o.live.interface;
  if (!capture.open(LiveCaptureSettings{name, o.ports, o.live.filter})) {
    std::fprintf(stderr, "pvtap: cannot capture on %s: %s\n", name.c_str(),
                 capture.error().c_str());
    return false;
  }
  for (const std::string& warning : capture.warnings()) {
    std::fprintf(stderr, "pvtap: %s: %s\n", name.c_str(), warning.c_str());
  }
  std::fprintf(stderr, "pvtap: capturing on %s, link type %s, filter \"%s\"\n", name.c_str(),
               capture.link_type_name().c_str(), capture.filter().c_str());
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

bool AuditRun::read_live_interface() {
  const std::string& name = options_.live.interface;
  LiveCapture capture;
  if (!open_capture(capture, options_)) return false;
  // on_network_packet decodes by the link type, as for a capture file.
  link_type_ = capture.link_type();
  const InputKind kind = *input_kind_of(link_type_);
  network_ = kind == InputKind::Network;
  status_ = std::make_unique<StatusLine>(options_.live.status_line);
  const auto handler = [this, kind](const CapturedPacket& packet) {
    last_time_ = std::max(last_time_, packet.time);
    on_record(kind, packet);
  };
  const double started = wall_clock_seconds();
  while (!live_should_stop(started)) {
    double wake = wall_clock_seconds() + kTick;
    if (options_.live.duration > 0) wake = std::min(wake, started + options_.live.duration);
    wait_for_packets(capture.selectable_fd(), wake);
    // Read before the packets are taken: a reply captured after it cannot be late for it.
    const double now = wall_clock_seconds();
    const int taken = capture.dispatch(kPacketsPerWake, handler);
    if (taken < 0) {
      status_->clear();
      std::fprintf(stderr, "pvtap: %s: capture stopped: %s\n", name.c_str(),
                   capture.error().c_str());
      break;
    }
    // A full batch leaves packets waiting: the sessions may only know the time up to the
    // last one taken, or a reply still waiting would count as missing.
    after_live_wake(taken < kPacketsPerWake ? now : last_time_);
  }
  // --count stops at a frame: what came after it stays out.
  if (!count_reached()) drain(capture, handler);
  live_.interface = interface_report(capture, name);
  end_live_capture(started, wall_clock_seconds());
  return true;
}

void AuditRun::after_live_wake(double now) {
  for (auto& bus : buses_) bus->session.idle(now);
  flush_live_output(now);
}

}  // namespace pvtap::analyzer
