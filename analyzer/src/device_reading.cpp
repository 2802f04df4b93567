// Placeholder until serial taps land.
#include <cstdio>

#include "audit_run.h"

namespace pvtap::analyzer {

bool AuditRun::read_devices() {
  std::fprintf(stderr, "pvtap: --device is not available yet\n");
  return false;
}

}  // namespace pvtap::analyzer
