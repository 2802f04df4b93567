// Fuzz target extcap_arguments: the parser of Wireshark's extcap command lines, and the check
// of the capture settings they carry, on arbitrary argument lists (NUL-separated in the input).
// Also the interface list answer for a port named by the input (names come from the system).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "extcap/extcap_arguments.h"
#include "extcap/extcap_options.h"
#include "extcap/extcap_sentences.h"
#include "fuzz_input.h"

namespace {}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace pvtap::analyzer;
  const auto args = pvtap::fuzz::nul_separated_arguments(data, size);
  (void)looks_like_extcap_call(args);
  const ExtcapCall call = parse_extcap_call(args);
  (void)settings_problems(call.settings);
  if (!call.interface.empty()) {
    const std::vector<DiscoveredPort> ports{
        {"/dev/" + call.interface, call.interface, "pvtap-" + call.interface}};
    (void)interfaces_answer(ports);
  }
  return 0;
}
