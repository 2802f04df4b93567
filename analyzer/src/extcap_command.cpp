// Placeholder until the extcap helper lands.
#include "extcap_command.h"

namespace pvtap::analyzer {

bool is_extcap_call(int, char**) {
  return false;
}

int run_extcap(int, char**) {
  return 2;
}

}  // namespace pvtap::analyzer
