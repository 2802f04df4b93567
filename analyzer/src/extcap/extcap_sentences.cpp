#include "extcap/extcap_sentences.h"

#include "extcap/extcap_options.h"
#include "pvtap/capture/link_types.h"

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

std::string config_answer() {
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
  return out;
}

}  // namespace pvtap::analyzer
