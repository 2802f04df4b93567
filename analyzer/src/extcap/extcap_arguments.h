// ExtcapCall: one call of Wireshark's extcap contract, read from the command line Wireshark
// (or tshark, or dumpcap) built: which question it asks and the capture settings it passes.
#pragma once

#include <string>
#include <vector>

namespace pvtap::analyzer {

enum class ExtcapAction {
  None,            // no extcap action was named
  ListInterfaces,  // --extcap-interfaces
  ListDlts,        // --extcap-dlts --extcap-interface IF
  ListConfig,      // --extcap-config [--extcap-interface IF]
  CheckFilter,     // --extcap-capture-filter F --extcap-interface IF, without --capture
  Capture,         // --capture --extcap-interface IF --fifo PATH
};

// The capture settings of the options dialog, as Wireshark passes them (the names and the
// defaults declared by --extcap-config, see extcap_sentences.h).
struct ExtcapSettings {
  std::string baud = "9600";
  std::string parity = "none";   // none, even or odd
  std::string stop_bits = "1";   // 1 or 2
  std::string dialect = "auto";  // auto, ascii, hybrid or gsl
  // A 4-wire bus: the interface of the tap on the replies' pair (the capture's own interface
  // is then the requests' pair), or "none" for a 2-wire bus.
  std::string duplex_replies = "none";
};

struct ExtcapCall {
  ExtcapAction action = ExtcapAction::None;
  std::string interface;
  std::string fifo;
  std::string capture_filter;
  ExtcapSettings settings;
  // Options pvtap does not know (newer Wireshark versions add some); they are skipped, not
  // refused, so that a Wireshark update does not break the capture.
  std::vector<std::string> ignored;
  // Problems with what was passed (an option without its value); empty when none.
  std::vector<std::string> problems;
};

// True when the command line is an extcap call rather than a `pvtap audit`/`pvtap sniff`.
bool looks_like_extcap_call(const std::vector<std::string>& args);

// Reads an extcap command line (`args` without the program name). Both `--name value` and
// `--name=value` are read, as Wireshark uses both.
ExtcapCall parse_extcap_call(const std::vector<std::string>& args);

}  // namespace pvtap::analyzer
