// LiveCaptureSetup: creating, configuring and activating a libpcap capture, and the errors of
// each step in the words a user needs.
#include "sources/live_capture_setup.h"

#include <pcap/pcap.h>

#include <fstream>
#include <sstream>

#include "pvtap/pcap/link_types.h"

namespace pvtap::analyzer {
namespace {

constexpr int kSnapLength = 65535;
// With immediate mode packets come at once; the timeout only bounds a blocking read.
constexpr int kTimeoutMs = 10;
constexpr int kCapNetAdmin = 12;  // capability bit numbers (linux/capability.h)
constexpr int kCapNetRaw = 13;

// The process's effective capability set, from /proc; nullopt when it cannot be read.
std::optional<std::uint64_t> effective_capabilities() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("CapEff:", 0) != 0) continue;
    std::uint64_t bits = 0;
    std::istringstream(line.substr(7)) >> std::hex >> bits;
    return bits;
  }
  return std::nullopt;
}

// Which capabilities the process lacks for capturing, e.g. "CAP_NET_RAW and CAP_NET_ADMIN".
std::string missing_capabilities() {
  const auto caps = effective_capabilities();
  const bool raw = caps && (*caps >> kCapNetRaw & 1) != 0;
  const bool admin = caps && (*caps >> kCapNetAdmin & 1) != 0;
  if (!raw && !admin) return "CAP_NET_RAW and CAP_NET_ADMIN";
  if (!raw) return "CAP_NET_RAW";
  if (!admin) return "CAP_NET_ADMIN";
  return "none of them (yet the kernel refused: a security module or container may forbid it)";
}

std::string permission_denied(const std::string& pcap_text) {
  return "permission denied (" + pcap_text +
         "): capturing needs root or CAP_NET_RAW and CAP_NET_ADMIN, and this process lacks " +
         missing_capabilities() +
         "; grant them with `sudo setcap cap_net_raw,cap_net_admin+eip $(command -v pvtap)`";
}

// pcap_activate's failure in the words a user needs.
std::string activate_failure(int rc, const std::string& interface, const std::string& text) {
  const bool not_permitted = text.find("Operation not permitted") != std::string::npos;
  if (rc == PCAP_ERROR_PERM_DENIED || not_permitted) return permission_denied(text);
  if (rc == PCAP_ERROR_NO_SUCH_DEVICE) {
    return "no such interface \"" + interface + "\" (" + text +
           "); `ip link` lists the interfaces there are";
  }
  if (rc == PCAP_ERROR_IFACE_NOT_UP) {
    return "the interface is down; bring it up with `ip link set " + interface + " up`";
  }
  return text.empty() ? pcap_statustostr(rc) : text;
}

// Sets the capture's options before it is activated; false with `error` set.
bool configure(pcap_t* pcap, std::string& error) {
  const int results[] = {
      pcap_set_snaplen(pcap, kSnapLength),
      pcap_set_promisc(pcap, 0),
      pcap_set_immediate_mode(pcap, 1),  // frames are reported as they cross, not in batches
      pcap_set_timeout(pcap, kTimeoutMs),
  };
  for (const int rc : results) {
    if (rc != 0) {
      error = std::string("cannot set up the capture: ") + pcap_statustostr(rc);
      return false;
    }
  }
  // Nanoseconds when the kernel has them; else microseconds, which is not an error: the
  // precision in force is read back once the capture is active. (libpcap 1.10.5 marks the
  // result as one that must be used.)
  [[maybe_unused]] const bool nanoseconds =
      pcap_set_tstamp_precision(pcap, PCAP_TSTAMP_PRECISION_NANO) == 0;
  return true;
}

std::string port_clause(const std::vector<std::uint16_t>& ports) {
  std::string out;
  for (const std::uint16_t port : ports) {
    const std::string p = std::to_string(port);
    if (!out.empty()) out += " or ";
    out += "tcp port " + p + " or udp port " + p;
  }
  return out;
}

bool activate(PcapHandle& pcap, const std::string& interface, LiveCaptureSetup& setup,
              std::string& error) {
  char errbuf[PCAP_ERRBUF_SIZE] = {};
  pcap.reset(pcap_create(interface.c_str(), errbuf));
  if (!pcap) {
    error = errbuf;
    return false;
  }
  if (!configure(pcap.get(), error)) return false;
  const int rc = pcap_activate(pcap.get());
  if (rc < 0) {
    error = activate_failure(rc, interface, pcap_geterr(pcap.get()));
    return false;
  }
  if (rc > 0) {
    const std::string text = pcap_geterr(pcap.get());
    setup.warnings.push_back(text.empty() ? pcap_statustostr(rc) : text);
  }
  setup.nanoseconds = pcap_get_tstamp_precision(pcap.get()) == PCAP_TSTAMP_PRECISION_NANO;
  return true;
}

bool check_link_type(pcap_t* pcap, LiveCaptureSetup& setup, std::string& error) {
  setup.link_type = pcap_datalink(pcap);
  if (setup.link_type < 0) {
    error = pcap_geterr(pcap);
    return false;
  }
  if (!input_kind_of(setup.link_type)) {
    error = "unsupported link type " + setup.link_type_name() +
            "; supported: " + supported_link_types_text();
    return false;
  }
  return true;
}

bool apply_filter(pcap_t* pcap, const std::string& text, LiveCaptureSetup& setup,
                  std::string& error) {
  bpf_program program{};
  if (pcap_compile(pcap, &program, text.c_str(), 1, PCAP_NETMASK_UNKNOWN) != 0) {
    error = "invalid capture filter \"" + text + "\": " + pcap_geterr(pcap);
    return false;
  }
  const int rc = pcap_setfilter(pcap, &program);
  pcap_freecode(&program);
  if (rc != 0) {
    error = "cannot set the capture filter \"" + text + "\": " + pcap_geterr(pcap);
    return false;
  }
  setup.filter = text;
  return true;
}

}  // namespace

void PcapClose::operator()(pcap_t* pcap) const {
  pcap_close(pcap);
}

std::string live_capture_filter(const std::vector<std::uint16_t>& ports,
                                const std::string& user_filter) {
  const std::string by_port = port_clause(ports);
  if (by_port.empty()) return user_filter.empty() ? "" : "(" + user_filter + ")";
  if (user_filter.empty()) return "(" + by_port + ")";
  return "(" + by_port + ") and (" + user_filter + ")";
}

std::string LiveCaptureSetup::link_type_name() const {
  return pvtap::link_type_name(link_type);
}

bool set_up_live_capture(const LiveCaptureSettings& settings, PcapHandle& pcap,
                         LiveCaptureSetup& setup, std::string& error) {
  if (!activate(pcap, settings.interface, setup, error)) return false;
  if (!check_link_type(pcap.get(), setup, error)) return false;
  const std::string filter = live_capture_filter(settings.ports, settings.filter);
  return filter.empty() || apply_filter(pcap.get(), filter, setup, error);
}

}  // namespace pvtap::analyzer
