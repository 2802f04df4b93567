// LanCapture: a LAN carrier's planned TCP segments and what its ground truth says of them.
#pragma once

#include <vector>

#include "lan/lan_exchanges.h"
#include "lan/tcp_session.h"

namespace pvtap::sim {

struct LanCapture {
  LanEndpoints ends;
  std::vector<LanSegment> segments;
  LanTruth truth;
};

}  // namespace pvtap::sim
