// Finds the serial ports that Wireshark lists as "RS485 tap (...)" capture interfaces.
#pragma once

#include <string>
#include <vector>

namespace pvtap::analyzer {

// DiscoveredPort: one port as a capture interface.
struct DiscoveredPort {
  std::string path;       // what the capture opens: the /dev/serial/by-id link when there is one
  std::string name;       // the short name shown: "ttyUSB0", "pts/3", "/tmp/ttyV0"
  std::string interface;  // Wireshark's interface name: "pvtap-" and a stable id
};

// Where ports are looked for; the defaults are the system's, tests point them elsewhere.
struct PortPlaces {
  std::string dev = "/dev";
  std::string sys_tty = "/sys/class/tty";  // tells built-in UARTs (ttyS*) that exist
  // Ports discovery cannot find (ptys of socat or an RFC 2217 client, ttyAMA*, ...), from
  // the environment variable PVTAP_SERIAL_PORTS: paths separated by ':'.
  std::vector<std::string> extra;
};

// The name of the environment variable with the extra ports.
inline constexpr const char* kExtraPortsVariable = "PVTAP_SERIAL_PORTS";

// The system's places, with the extra ports of PVTAP_SERIAL_PORTS.
PortPlaces system_port_places();

// Splits a PVTAP_SERIAL_PORTS value into paths (empty entries are skipped).
std::vector<std::string> split_port_list(const std::string& value);

// The ports that exist: adapters under dev/serial/by-id, then dev/ttyUSB*, dev/ttyACM* not
// already listed through a by-id link, then ttyS* with a UART behind them, then the extra
// ports that exist. Each port appears once, however many names lead to it.
std::vector<DiscoveredPort> discover_serial_ports(const PortPlaces& places);

}  // namespace pvtap::analyzer
