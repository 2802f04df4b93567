#include "extcap/extcap_sentences.h"

#include "extcap/extcap_options.h"
#include "pvtap/pcap/link_types.h"

namespace pvtap::analyzer {
namespace {

// Shown in Wireshark's About › Plugins: the version of project() in CMakeLists.txt.
constexpr const char* kExtcapVersion = PVTAP_VERSION;

// Sentence values cannot hold the delimiters; names of ports and settings never do, but a
// path given through PVTAP_SERIAL_PORTS might.
std::string clean(std::string text) {
  for (char& c : text) {
    if (c == '{' || c == '}' || c == '\n' || c == '\r') c = '_';
  }
  return text;
}

std::string field(const char* name, const std::string& value) {
  return std::string("{") + name + "=" + clean(value) + "}";
}

}  // namespace

std::string interfaces_answer(const std::vector<DiscoveredPort>& ports) {
  std::string out = "extcap " + field("version", kExtcapVersion) + "\n";
  for (const DiscoveredPort& port : ports) {
    out += "interface " + field("value", port.interface) +
           field("display", "RS485 tap (" + port.name + ")") + "\n";
  }
  return out;
}

std::string dlts_answer() {
  return "dlt " + field("number", std::to_string(dlt::kUpperPdu)) + field("name", "pvtap") +
         field("display", "Exported PDUs (RS485 frames for the pvtap dissector)") + "\n";
}

namespace {

// The replies' pair of a 4-wire bus: any other port's tap. Its choices depend on the ports
// present, so it is not in the fixed table of extcap_options.h.
std::string duplex_answer(int number, const std::vector<DiscoveredPort>& ports,
                          const std::string& interface) {
  const std::string arg = std::to_string(number);
  std::string out = "arg " + field("number", arg) + field("call", "--duplex-replies") +
                    field("display", "4-wire: replies' pair") + field("type", "selector") +
                    field("default", kNoDuplex) +
                    field("tooltip",
                          "RS422 / 4-wire Modbus: the tap on the replies' pair; this interface is "
                          "then the requests' pair, and both are read as one bus (read-only)") +
                    field("group", "Serial line") + "\n";
  out += "value " + field("arg", arg) + field("value", kNoDuplex) +
         field("display", "None (2-wire: requests and replies on this pair)") +
         field("default", "true") + "\n";
  for (const DiscoveredPort& port : ports) {
    if (port.interface == interface) continue;
    out += "value " + field("arg", arg) + field("value", port.interface) +
           field("display", "RS485 tap (" + port.name + ")") + "\n";
  }
  return out;
}

}  // namespace

std::string config_answer(const std::vector<DiscoveredPort>& ports, const std::string& interface) {
  std::string out;
  int number = 0;
  for (const ExtcapOption& option : extcap_options()) {
    const std::string arg = std::to_string(number++);
    out += "arg " + field("number", arg) + field("call", option.call) +
           field("display", option.display) + field("type", "selector") +
           field("default", option.default_value) + field("tooltip", option.tooltip) +
           field("group", option.group) + "\n";
    for (const ExtcapChoice& choice : option.choices) {
      out += "value " + field("arg", arg) + field("value", choice.value) +
             field("display", choice.display);
      if (choice.value == option.default_value) out += field("default", "true");
      out += "\n";
    }
  }
  return out + duplex_answer(number, ports, interface);
}

}  // namespace pvtap::analyzer
