#include "extcap/extcap_capture.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <string>
#include <thread>

#include "cli/exit_status.h"
#include "cli/sniff_command.h"
#include "extcap/extcap_options.h"
#include "extcap/extcap_sentences.h"
#include "sources/stop_signal.h"

namespace pvtap::analyzer {
namespace {

// Set when a write to the fifo found Wireshark's end closed.
volatile std::sig_atomic_t fifo_broken = 0;

extern "C" void on_broken_fifo(int) {
  fifo_broken = 1;
  request_stop();  // only sets a flag: safe in a signal handler
}

// Wireshark gone (crashed, or closed the fifo before its SIGTERM reached us): the next write
// raises SIGPIPE, whose default action would kill pvtap in mid-record. Instead the capture
// stops as on SIGTERM, and the reading loop sees the request at its next wake-up.
void stop_on_broken_fifo() {
  struct sigaction action {};
  action.sa_handler = on_broken_fifo;
  sigemptyset(&action.sa_mask);
  action.sa_flags = 0;
  sigaction(SIGPIPE, &action, nullptr);
}

// The port behind Wireshark's interface name; null when none is (unplugged, or "none").
const DiscoveredPort* port_named(const std::vector<DiscoveredPort>& ports,
                                 const std::string& interface) {
  const auto named =
      std::find_if(ports.begin(), ports.end(),
                   [&interface](const DiscoveredPort& p) { return p.interface == interface; });
  return named == ports.end() ? nullptr : &*named;
}

// Why a 4-wire capture cannot start; empty when it can (or the bus has 2 wires).
std::string duplex_problem(const ExtcapCall& call, const DiscoveredPort* replies) {
  const std::string& named = call.settings.duplex_replies;
  if (named == kNoDuplex) return {};
  if (named == call.interface) return "--duplex-replies names the requests' own tap";
  if (replies == nullptr) return "no serial port for the replies' pair " + named + " (unplugged?)";
  if (call.settings.baud == "auto") return "a 4-wire bus is read at one rate: choose the baud rate";
  return {};
}

// Why the call cannot start a capture; empty when it can. `replies`: the port of the replies'
// pair the call names, if any.
std::string call_problem(const ExtcapCall& call, const DiscoveredPort* port,
                         const DiscoveredPort* replies) {
  if (call.interface.empty()) return "--capture needs --extcap-interface";
  if (call.fifo.empty()) return "--capture needs --fifo";
  if (port == nullptr) {
    return "no serial port for interface " + call.interface +
           " (unplugged? ports that are not found by themselves go in " + kExtraPortsVariable + ")";
  }
  // The bytes of a serial line are no packets a BPF program could select; taking a filter
  // and passing everything would show the user traffic they meant to leave out.
  if (!call.capture_filter.empty()) {
    return kNoCaptureFilter;
  }
  const std::vector<std::string> problems = settings_problems(call.settings);
  return problems.empty() ? duplex_problem(call, replies) : problems.front();
}

// A refused call still opens and closes Wireshark's fifo: dumpcap may be blocked opening
// its reading end, and would wait for a writer that never comes (tshark then hangs on a loaded
// machine instead of showing why pvtap refused). Its reader may come a moment after us, so
// the open is tried for a while; the capture's end of file then ends dumpcap's wait.
void release_fifo(const std::string& fifo) {
  if (fifo.empty()) return;
  constexpr auto kPatience = std::chrono::seconds(2);
  constexpr auto kStep = std::chrono::milliseconds(20);
  const auto deadline = std::chrono::steady_clock::now() + kPatience;
  while (std::chrono::steady_clock::now() < deadline) {
    const int fd = ::open(fifo.c_str(), O_WRONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd >= 0) {
      ::close(fd);
      return;
    }
    if (errno != ENXIO) return;  // no fifo there, or not ours to open
    std::this_thread::sleep_for(kStep);
  }
}

}  // namespace

SniffOptions capture_options(const DiscoveredPort& port, const ExtcapSettings& settings,
                             const std::string& fifo) {
  SniffOptions o;
  o.live.devices = {port.path};
  o.live.line.parity = SerialLine::parity_letter(settings.parity);
  o.live.line.stop_bits = settings.stop_bits == "2" ? 2 : 1;
  o.live.search_line = settings.baud == "auto";
  if (!o.live.search_line) o.baud = static_cast<std::uint32_t>(std::stoul(settings.baud));
  o.dialect = settings.dialect;
  o.write_path = fifo;
  o.live.quiet = true;
  o.summary_only = true;
  return o;
}

int run_extcap_capture(const ExtcapCall& call, const std::vector<DiscoveredPort>& ports) {
  const DiscoveredPort* port = port_named(ports, call.interface);
  const DiscoveredPort* replies = port_named(ports, call.settings.duplex_replies);
  if (const std::string problem = call_problem(call, port, replies); !problem.empty()) {
    std::fprintf(stderr, "pvtap: %s\n", problem.c_str());
    std::fflush(stderr);
    release_fifo(call.fifo);
    return kExitBadInput;
  }
  SniffOptions options = capture_options(*port, call.settings, call.fifo);
  if (replies != nullptr) {
    options.live.devices.push_back(replies->path);
    options.live.duplex = true;
  }
  stop_on_broken_fifo();
  const int status = run_live_capture(options);
  // Nobody reads the fifo any more, so the records it lost are no failure of the capture.
  return fifo_broken != 0 ? kExitOk : status;
}

}  // namespace pvtap::analyzer
