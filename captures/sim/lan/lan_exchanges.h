// The bus as a LAN client sees it: each request it sent and the reply the bus gave it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bus/bus_event.h"

namespace pvtap::sim {

// LanExchange: indexes into the timeline's events.
struct LanExchange {
  std::size_t request = 0;
  std::optional<std::size_t> reply;  // none: the bus gave no reply (a timeout)
};

// Requests in time order, each with the first reply before the next request.
std::vector<LanExchange> lan_exchanges(const BusTimeline& timeline);

// Removes the replies a carrier dropped and makes their requests timeouts (in request order);
// the timeline then is what the LAN side saw.
void drop_replies(BusTimeline& timeline, const std::vector<std::size_t>& replies);

// LanTruth: what the ground truth says of a LAN carrier: its counts, named as the readers'
// summaries name them, and one JSON object per carrier frame.
struct LanTruth {
  std::string carrier;    // "v5", "mbap", "logic"
  std::string list_name;  // the frames' key; empty: carrier + "_frames"
  std::vector<std::pair<std::string, std::uint64_t>> counts;
  std::vector<std::string> frames;
};

}  // namespace pvtap::sim
