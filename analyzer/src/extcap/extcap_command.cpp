#include "extcap/extcap_command.h"

#include <cstdio>
#include <string>
#include <vector>

#include "cli/exit_status.h"
#include "extcap/extcap_arguments.h"
#include "extcap/extcap_capture.h"
#include "extcap/extcap_port_discovery.h"
#include "extcap/extcap_sentences.h"

namespace pvtap::analyzer {
namespace {

std::vector<std::string> arguments_of(int argc, char** argv) {
  return argc > 1 ? std::vector<std::string>(argv + 1, argv + argc) : std::vector<std::string>{};
}

int answer(const std::string& text) {
  std::fputs(text.c_str(), stdout);
  return std::fflush(stdout) == 0 ? kExitOk : kExitBadInput;
}

// Wireshark validates a capture filter by the output: nothing means valid, a line is the
// error it shows. A serial tap has no packets to filter, so only the empty filter is valid.
int check_filter(const ExtcapCall& call) {
  if (call.capture_filter.empty()) return kExitOk;
  return answer(std::string(kNoCaptureFilter) + "\n");
}

}  // namespace

bool is_extcap_call(int argc, char** argv) {
  return looks_like_extcap_call(arguments_of(argc, argv));
}

int run_extcap(int argc, char** argv) {
  const ExtcapCall call = parse_extcap_call(arguments_of(argc, argv));
  for (const std::string& problem : call.problems) {
    std::fprintf(stderr, "pvtap: %s\n", problem.c_str());
  }
  if (!call.problems.empty()) return kExitBadInput;
  switch (call.action) {
    case ExtcapAction::ListInterfaces:
      return answer(interfaces_answer(discover_serial_ports(system_port_places())));
    case ExtcapAction::ListDlts:
      return answer(dlts_answer());
    case ExtcapAction::ListConfig:
      return answer(config_answer(discover_serial_ports(system_port_places()), call.interface));
    case ExtcapAction::CheckFilter:
      return check_filter(call);
    case ExtcapAction::Capture:
      return run_extcap_capture(call, discover_serial_ports(system_port_places()));
    case ExtcapAction::None:
      break;
  }
  std::fprintf(stderr,
               "pvtap: an extcap call needs --extcap-interfaces, --extcap-dlts, "
               "--extcap-config or --capture\n");
  return kExitBadInput;
}

}  // namespace pvtap::analyzer
