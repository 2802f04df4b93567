// Placeholder until the live interface helper lands.
#include <cstdio>

#include "audit_run.h"

namespace pvtap::analyzer {

bool AuditRun::read_live_interface() {
  std::fprintf(stderr, "pvtap: --interface is not available yet\n");
  return false;
}

}  // namespace pvtap::analyzer
