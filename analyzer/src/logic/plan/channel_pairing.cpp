// pair_channels: bursts compared over the stretch both channels were probed in.
#include "logic/plan/channel_pairing.h"

#include <algorithm>

namespace pvtap::analyzer {
namespace {

// Pairs need this many bursts between them, and this share of turns from one to the other.
constexpr std::size_t kFewestBursts = 4;
constexpr double kTurnShare = 0.8;

struct Turns {
  bool alternate = false;
  bool first_asks = true;  // the first channel's bursts are the requests
  double share = 0;
};

// Merged in time order, the bursts change channel at most turns; the channel answered sooner
// (request to reply) than it is asked again (reply to the next request) asks.
Turns turns_of(const ProbedChannel& a, const ProbedChannel& b) {
  const std::uint64_t until = std::min(a.probed, b.probed);
  std::vector<std::pair<Burst, int>> all;
  for (const Burst& x : a.bursts)
    if (x.end <= until) all.push_back({x, 0});
  for (const Burst& x : b.bursts)
    if (x.end <= until) all.push_back({x, 1});
  std::sort(all.begin(), all.end(),
            [](const auto& x, const auto& y) { return x.first.start < y.first.start; });
  Turns t;
  if (all.size() < kFewestBursts) return t;
  std::size_t changes = 0;
  double gap[2] = {0, 0};
  std::size_t gaps[2] = {0, 0};
  for (std::size_t i = 1; i < all.size(); ++i) {
    if (all[i].first.start < all[i - 1].first.end) return t;  // both talk at once: not a pair
    if (all[i].second == all[i - 1].second) continue;
    ++changes;
    const auto from = static_cast<std::size_t>(all[i - 1].second);
    gap[from] += static_cast<double>(all[i].first.start - all[i - 1].first.end);
    ++gaps[from];
  }
  t.share = static_cast<double>(changes) / static_cast<double>(all.size() - 1);
  t.alternate = t.share >= kTurnShare && gaps[0] > 0 && gaps[1] > 0;
  if (t.alternate)
    t.first_asks = gap[0] / static_cast<double>(gaps[0]) <= gap[1] / static_cast<double>(gaps[1]);
  return t;
}

// What the frames say: +1 when `a` carries requests and `b` replies, -1 for the reverse, 0
// when they do not say (writes read alike both ways, or too few frames).
int role_vote(const ProbedChannel& a, const ProbedChannel& b) {
  const auto lean = [](const ProbedChannel& p) {
    const FormatTrial& t = p.line->trial;
    return static_cast<double>(t.requests) - static_cast<double>(t.responses);
  };
  if (lean(a) > 0 && lean(b) < 0) return 1;
  if (lean(a) < 0 && lean(b) > 0) return -1;
  return 0;
}

}  // namespace

std::vector<Burst> bursts_of(const std::vector<SampleRun>& runs, const DetectedLine& line) {
  const double apart =
      3.5 * line.samples_per_bit() * static_cast<double>(line.line.format.bits_per_char());
  const bool space = line.line.format.inverted;  // the level of a start bit
  std::vector<Burst> out;
  std::uint64_t at = 0;
  for (const SampleRun& r : runs) {
    if (r.level == space) {
      if (!out.empty() && static_cast<double>(at - out.back().end) < apart) {
        out.back().end = at + r.count;
      } else {
        out.push_back({at, at + r.count});
      }
    }
    at += r.count;
  }
  return out;
}

std::vector<std::vector<std::size_t>> pair_channels(const std::vector<ProbedChannel>& channels) {
  std::vector<std::vector<std::size_t>> buses;
  std::vector<bool> taken(channels.size(), false);
  for (std::size_t i = 0; i < channels.size(); ++i) {
    if (taken[i]) continue;
    taken[i] = true;
    std::vector<std::size_t> bus{i};
    // The best partner among the channels whose frames check too.
    Turns best;
    std::size_t partner = i;
    for (std::size_t j = i + 1; j < channels.size() && channels[i].line->trial.good_frames; ++j) {
      if (taken[j] || channels[j].line->trial.good_frames == 0) continue;
      const Turns t = turns_of(channels[i], channels[j]);
      if (t.alternate && t.share > best.share) {
        best = t;
        partner = j;
      }
    }
    if (partner != i) {
      taken[partner] = true;
      // The frames' layouts say which side asks; the pauses only where they do not (a slow
      // reply or two make the mean wait for replies look longer than the master's).
      const int vote = role_vote(channels[i], channels[partner]);
      const bool first_asks = vote != 0 ? vote > 0 : best.first_asks;
      bus =
          first_asks ? std::vector<std::size_t>{i, partner} : std::vector<std::size_t>{partner, i};
    }
    buses.push_back(std::move(bus));
  }
  return buses;
}

}  // namespace pvtap::analyzer
