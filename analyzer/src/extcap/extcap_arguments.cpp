#include "extcap/extcap_arguments.h"

#include <algorithm>
#include <array>
#include <string_view>

namespace pvtap::analyzer {
namespace {

// Options that name what Wireshark asks for; any of them makes the call an extcap call.
constexpr std::array<std::string_view, 6> kExtcapMarkers = {
    "--extcap-interfaces", "--extcap-dlts",      "--extcap-config",
    "--capture",           "--extcap-interface", "--extcap-capture-filter"};

// Options of the contract (and of pvtap's settings) that take a value.
constexpr std::array<std::string_view, 14> kValueOptions = {"--extcap-interface",
                                                            "--fifo",
                                                            "--extcap-capture-filter",
                                                            "--extcap-version",
                                                            "--extcap-control-in",
                                                            "--extcap-control-out",
                                                            "--extcap-reload-option",
                                                            "--baud",
                                                            "--parity",
                                                            "--stop-bits",
                                                            "--dialect",
                                                            "--duplex-replies",
                                                            "--log-level",
                                                            "--log-file"};

template <std::size_t N>
bool is_one_of(std::string_view name, const std::array<std::string_view, N>& names) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

bool is_option(std::string_view arg) {
  return arg.size() > 2 && arg.substr(0, 2) == "--";
}

// The option's name without an attached `=value`.
std::string_view option_name(std::string_view arg) {
  return arg.substr(0, arg.find('='));
}

void set_flag(ExtcapCall& call, std::string_view name) {
  if (name == "--extcap-interfaces") {
    call.action = ExtcapAction::ListInterfaces;
  } else if (name == "--extcap-dlts") {
    call.action = ExtcapAction::ListDlts;
  } else if (name == "--extcap-config") {
    call.action = ExtcapAction::ListConfig;
  } else if (name == "--capture") {
    call.action = ExtcapAction::Capture;
  }
}

// Stores a value option; the extcap bookkeeping ones pvtap has no use for are dropped.
void set_value(ExtcapCall& call, std::string_view name, const std::string& value) {
  if (name == "--extcap-interface") call.interface = value;
  if (name == "--fifo") call.fifo = value;
  if (name == "--extcap-capture-filter") call.capture_filter = value;
  if (name == "--baud") call.settings.baud = value;
  if (name == "--parity") call.settings.parity = value;
  if (name == "--stop-bits") call.settings.stop_bits = value;
  if (name == "--dialect") call.settings.dialect = value;
  if (name == "--duplex-replies") call.settings.duplex_replies = value;
}

}  // namespace

bool looks_like_extcap_call(const std::vector<std::string>& args) {
  // `pvtap audit ...` and `pvtap sniff ...` start with their subcommand; Wireshark's calls
  // start with an option.
  if (args.empty() || !is_option(args.front())) return false;
  return std::any_of(args.begin(), args.end(), [](const std::string& arg) {
    return is_one_of(option_name(arg), kExtcapMarkers);
  });
}

ExtcapCall parse_extcap_call(const std::vector<std::string>& args) {
  ExtcapCall call;
  bool has_capture_filter = false;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    if (!is_option(arg)) {
      call.ignored.push_back(arg);
      continue;
    }
    const std::string_view name = option_name(arg);
    const bool attached = name.size() < arg.size();
    const bool next_is_value = i + 1 < args.size() && !is_option(args[i + 1]);
    if (is_one_of(name, kValueOptions)) {
      if (attached) {
        set_value(call, name, arg.substr(name.size() + 1));
      } else if (i + 1 < args.size()) {
        // A value may itself start with "--" only when it is given with '='; a capture
        // filter or a path never does.
        set_value(call, name, args[++i]);
      } else {
        call.problems.push_back(std::string(name) + " needs a value");
        continue;
      }
      has_capture_filter = has_capture_filter || name == "--extcap-capture-filter";
    } else if (is_one_of(name, kExtcapMarkers)) {
      set_flag(call, name);
    } else {
      // Unknown: take the next word as its value when it is not an option itself.
      call.ignored.push_back(arg);
      if (!attached && next_is_value) call.ignored.push_back(args[++i]);
    }
  }
  // Wireshark validates a capture filter by calling with the filter and no action.
  if (call.action == ExtcapAction::None && has_capture_filter) {
    call.action = ExtcapAction::CheckFilter;
  }
  return call;
}

}  // namespace pvtap::analyzer
