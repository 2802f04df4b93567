#include "extcap/extcap_options.h"

#include <algorithm>

namespace pvtap::analyzer {
namespace {

std::vector<ExtcapChoice> same_shown(std::initializer_list<const char*> values) {
  std::vector<ExtcapChoice> choices;
  for (const char* value : values) choices.push_back({value, value});
  return choices;
}

// The rates `pvtap sniff --baud` accepts that inverters and loggers use, and its search.
std::vector<ExtcapChoice> baud_choices() {
  std::vector<ExtcapChoice> choices =
      same_shown({"2400", "4800", "9600", "19200", "38400", "57600", "115200"});
  choices.push_back({"auto", "Auto (found from the traffic; parity and stop bits too)"});
  return choices;
}

std::vector<ExtcapOption> build_options() {
  const ExtcapSettings defaults;
  return {
      {"--baud", "Baud rate",
       "The bus's speed; the tap must be set like the bus, or Auto finds the speed, parity and "
       "stop bits from the traffic (passively)",
       "Serial line", baud_choices(), defaults.baud, &ExtcapSettings::baud},
      {"--parity",
       "Parity",
       "Parity of the bus's characters",
       "Serial line",
       {{"none", "None"}, {"even", "Even"}, {"odd", "Odd"}},
       defaults.parity,
       &ExtcapSettings::parity},
      {"--stop-bits", "Stop bits", "Stop bits per character", "Serial line", same_shown({"1", "2"}),
       defaults.stop_bits, &ExtcapSettings::stop_bits},
      {"--dialect",
       "Dialect",
       "Dialects to recognize; auto finds all four",
       "Protocol",
       {{"auto", "Auto (ASCII, Hybrid V2.2, GSL, Modbus)"},
        {"ascii", "ASCII (Korean inverter protocol)"},
        {"hybrid", "Hybrid V2.2"},
        {"gsl", "GSL (KSTAR Modbus RTU)"},
        {"modbus", "Modbus RTU (meters, sensors, IO modules)"}},
       defaults.dialect,
       &ExtcapSettings::dialect},
  };
}

}  // namespace

const std::vector<ExtcapOption>& extcap_options() {
  static const std::vector<ExtcapOption> options = build_options();
  return options;
}

std::vector<std::string> settings_problems(const ExtcapSettings& settings) {
  std::vector<std::string> problems;
  for (const ExtcapOption& option : extcap_options()) {
    const std::string& value = settings.*option.setting;
    const auto is_value = [&value](const ExtcapChoice& choice) { return choice.value == value; };
    if (std::any_of(option.choices.begin(), option.choices.end(), is_value)) continue;
    std::string allowed;
    for (const ExtcapChoice& choice : option.choices) {
      allowed += (allowed.empty() ? "" : ", ") + choice.value;
    }
    problems.push_back(option.call + " " + value + ": not one of " + allowed);
  }
  return problems;
}

}  // namespace pvtap::analyzer
