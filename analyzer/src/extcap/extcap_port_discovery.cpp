#include "extcap/extcap_port_discovery.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <string_view>
#include <system_error>

namespace pvtap::analyzer {
namespace fs = std::filesystem;
namespace {

constexpr std::string_view kInterfacePrefix = "pvtap-";

// The file every name leads to, so that a port reached by two names is listed once.
std::string identity(const fs::path& path) {
  std::error_code error;
  const fs::path real = fs::canonical(path, error);
  return error ? path.string() : real.string();
}

bool path_exists(const fs::path& path) {
  std::error_code error;
  return fs::exists(path, error);
}

// The entries of `dir` whose names are `prefix` followed by digits, in numeric order
// (ttyUSB2 before ttyUSB10).
std::vector<std::string> numbered_entries(const fs::path& dir, std::string_view prefix) {
  std::vector<std::pair<unsigned long, std::string>> found;
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(dir, error)) {
    const std::string name = entry.path().filename().string();
    if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string digits = name.substr(prefix.size());
    if (!std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; })) {
      continue;
    }
    found.emplace_back(std::strtoul(digits.c_str(), nullptr, 10), name);
  }
  std::sort(found.begin(), found.end());
  std::vector<std::string> names;
  for (auto& [number, name] : found) names.push_back(std::move(name));
  return names;
}

// Every ttyS0..ttyS31 device node exists whether a UART is there or not; the kernel's serial
// core reports the UART type in sysfs, 0 (PORT_UNKNOWN) when there is none.
bool has_uart(const fs::path& sys_tty, const std::string& name) {
  std::ifstream type_file(sys_tty / name / "type");
  int type = 0;
  return static_cast<bool>(type_file >> type) && type != 0;
}

// Wireshark keys saved options by interface name; a name made of the path stays the same
// from one session to the next.
std::string interface_for(std::string id) {
  std::replace(id.begin(), id.end(), '/', '-');
  return std::string(kInterfacePrefix) + id;
}

class PortList {
 public:
  // Adds the port unless a port already listed is the same file.
  void add(const fs::path& path, std::string name, std::string id) {
    if (!seen_.insert(identity(path)).second) return;
    ports_.push_back(DiscoveredPort{path.string(), std::move(name), interface_for(std::move(id))});
  }
  std::vector<DiscoveredPort> take() { return std::move(ports_); }

 private:
  std::set<std::string> seen_;
  std::vector<DiscoveredPort> ports_;
};

void add_by_id(const fs::path& dev, PortList& ports) {
  std::vector<fs::path> links;
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(dev / "serial" / "by-id", error)) {
    links.push_back(entry.path());
  }
  std::sort(links.begin(), links.end());
  for (const fs::path& link : links) {
    if (!path_exists(link)) continue;  // a link left behind by an adapter that is gone
    // Shown by the tty it leads to (what users know the adapter as), kept by its by-id name
    // (which survives a replug into another USB port).
    const std::string tty = fs::path(identity(link)).filename().string();
    ports.add(link, tty, link.filename().string());
  }
}

// The name shown for a path: relative to dev when it is under it ("pts/3"), else the path.
std::string shown_name(const fs::path& dev, const std::string& path) {
  const std::string prefix = dev.string() + "/";
  if (path.compare(0, prefix.size(), prefix) == 0) return path.substr(prefix.size());
  return path;
}

}  // namespace

std::vector<std::string> split_port_list(const std::string& value) {
  std::vector<std::string> paths;
  std::size_t start = 0;
  while (start <= value.size()) {
    std::size_t end = value.find(':', start);
    if (end == std::string::npos) end = value.size();
    if (end > start) paths.push_back(value.substr(start, end - start));
    start = end + 1;
  }
  return paths;
}

PortPlaces system_port_places() {
  PortPlaces places;
  if (const char* extra = std::getenv(kExtraPortsVariable)) places.extra = split_port_list(extra);
  return places;
}

std::vector<DiscoveredPort> discover_serial_ports(const PortPlaces& places) {
  const fs::path dev = places.dev;
  PortList ports;
  add_by_id(dev, ports);
  for (const char* prefix : {"ttyUSB", "ttyACM"}) {
    for (const std::string& name : numbered_entries(dev, prefix)) ports.add(dev / name, name, name);
  }
  for (const std::string& name : numbered_entries(places.sys_tty, "ttyS")) {
    if (has_uart(places.sys_tty, name) && path_exists(dev / name))
      ports.add(dev / name, name, name);
  }
  for (const std::string& path : places.extra) {
    if (!path_exists(path)) continue;
    std::string name = shown_name(dev, path);
    std::string id = name.front() == '/' ? name.substr(1) : name;
    ports.add(path, std::move(name), std::move(id));
  }
  return ports.take();
}

}  // namespace pvtap::analyzer
