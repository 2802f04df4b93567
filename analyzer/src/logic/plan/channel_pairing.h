// Which channels are the two directions of one bus: without --channels, two channels whose
// bursts never overlap and take turns (a request on one, its reply on the other) are one bus.
#pragma once

#include <cstdint>
#include <vector>

#include "logic/plan/line_probe.h"

namespace pvtap::analyzer {

// The stretches of a channel's first samples where its UART talks, apart by 3.5 characters.
std::vector<Burst> bursts_of(const std::vector<SampleRun>& runs, const DetectedLine& line);

// The buses over `channels` (indexes; a pair is requests first, then replies), in the order
// of their first channel.
std::vector<std::vector<std::size_t>> pair_channels(const std::vector<ProbedChannel>& channels);

}  // namespace pvtap::analyzer
