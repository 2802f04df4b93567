// The capture options pvtap offers in Wireshark's options dialog for an RS485 tap: one table
// that both the --extcap-config answer and the check of a --capture call read.
#pragma once

#include <string>
#include <vector>

#include "extcap/extcap_arguments.h"

namespace pvtap::analyzer {

struct ExtcapChoice {
  std::string value;    // as passed on the command line
  std::string display;  // as shown in the dialog
};

struct ExtcapOption {
  std::string call;  // "--baud"
  std::string display;
  std::string tooltip;
  std::string group;  // the dialog's tab
  std::vector<ExtcapChoice> choices;
  std::string default_value;
  std::string ExtcapSettings::*setting;  // where a --capture call's value lands
};

// Baud rate, parity, stop bits and dialect, in the dialog's order.
const std::vector<ExtcapOption>& extcap_options();

// One line per setting whose value is not one of its choices; empty when all are fine.
std::vector<std::string> settings_problems(const ExtcapSettings& settings);

}  // namespace pvtap::analyzer
