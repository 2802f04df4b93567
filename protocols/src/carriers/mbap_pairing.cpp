#include "pvtap/carriers/mbap_pairing.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pvtap {

MbapPairing::MbapPairing(double timeout, MbapReleaseSink& sink) : timeout_(timeout), sink_(sink) {}

void MbapPairing::hand_on(const Held& h) {
  sink_.release(
      MbapRelease{Direction::ToSlave, h.offset, h.transaction, {h.frame.data(), h.size}, h.time});
}

void MbapPairing::request(const MbapAdu& adu) {
  advance(adu.time);
  // A reused transaction id ends the wait of the request that had it.
  const auto same = std::find_if(held_.begin(), held_.end(),
                                 [&](const Held& h) { return h.transaction == adu.transaction; });
  if (same != held_.end()) {
    hand_on(*same);
    held_.erase(same);
  }
  Held h;
  h.offset = adu.offset;
  h.transaction = adu.transaction;
  h.time = adu.time;
  h.size = static_cast<std::uint8_t>(adu.frame.size());
  std::copy(adu.frame.begin(), adu.frame.end(), h.frame.begin());
  held_.push_back(h);
}

void MbapPairing::reply(const MbapAdu& adu) {
  advance(adu.time);
  const auto asked = std::find_if(held_.begin(), held_.end(),
                                  [&](const Held& h) { return h.transaction == adu.transaction; });
  const bool answers = asked != held_.end();
  if (answers) {
    hand_on(*asked);
    held_.erase(asked);
  }
  sink_.release(
      MbapRelease{Direction::FromSlave, adu.offset, adu.transaction, adu.frame, adu.time, answers});
}

void MbapPairing::advance(double now) {
  // Held oldest first: the overdue ones are a prefix.
  auto it = held_.begin();
  while (it != held_.end() && now >= due(*it)) {
    hand_on(*it);
    ++it;
  }
  held_.erase(held_.begin(), it);
}

double MbapPairing::due(const Held& h) const {
  return std::nextafter(h.time + timeout_, std::numeric_limits<double>::infinity());
}

std::optional<double> MbapPairing::next_deadline() const {
  if (held_.empty()) return std::nullopt;
  return due(held_.front());
}

void MbapPairing::finish() {
  for (const Held& h : held_) hand_on(h);
  held_.clear();
}

}  // namespace pvtap
