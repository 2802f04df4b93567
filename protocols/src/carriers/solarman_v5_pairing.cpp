#include "pvtap/carriers/solarman_v5_pairing.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pvtap::solarman_v5 {

SolarmanV5Pairing::SolarmanV5Pairing(double timeout, ReleaseSink& sink)
    : timeout_(timeout), sink_(sink) {}

void SolarmanV5Pairing::hand_on(const Waiting& w) {
  Release r;
  r.kind = Release::Kind::Request;
  r.rtu = {w.rtu.data(), w.size};
  r.time = w.time;
  r.offset = w.offset;
  r.sequence = w.sequence;
  r.serial = w.serial;
  sink_.release(r);
}

void SolarmanV5Pairing::frame(const Frame& f, double time, std::uint64_t offset) {
  if (f.kind == FrameKind::Response || f.kind == FrameKind::StickFrame) {
    stick_serial_ = f.header.serial;
  }
  advance(time);
  if (f.kind == FrameKind::Request && f.rtu_length > 0) request(f, time, offset);
  if (f.kind == FrameKind::Response && (f.rtu_length > 0 || f.stick_code)) {
    response(f, time, offset);
  }
  promote();
}

void SolarmanV5Pairing::request(const Frame& f, double time, std::uint64_t offset) {
  const std::uint8_t sequence = client_sequence(f.header);
  // A reused sequence byte ends the wait of the request that had it.
  if (on_bus_ && on_bus_->sequence == sequence) on_bus_.reset();
  const auto same = std::find_if(held_.begin(), held_.end(),
                                 [&](const Waiting& w) { return w.sequence == sequence; });
  if (same != held_.end()) {
    hand_on(*same);
    held_.erase(same);
  }
  Waiting& w = held_.emplace_back();
  w.number = requests_++;
  w.offset = offset;
  w.sequence = sequence;
  w.serial = f.header.serial;
  w.time = time;
  w.size = std::min(f.rtu_length, w.rtu.size());
  const auto rtu = f.rtu();
  std::copy_n(rtu.begin(), w.size, w.rtu.begin());
}

void SolarmanV5Pairing::promote() {
  while (!on_bus_ && !held_.empty()) {
    if (!for_this_stick(held_.front())) return;  // the stick says whether it takes it
    hand_on(held_.front());
    on_bus_ = held_.front();
    held_.erase(held_.begin());
  }
}

std::vector<SolarmanV5Pairing::Waiting>::iterator SolarmanV5Pairing::release_older(
    std::vector<Waiting>::iterator asked) {
  for (auto it = held_.begin(); it != asked; ++it) hand_on(*it);
  return held_.erase(held_.begin(), asked);
}

void SolarmanV5Pairing::response(const Frame& f, double time, std::uint64_t offset) {
  const std::uint8_t sequence = client_sequence(f.header);
  const bool answers_on_bus = on_bus_ && on_bus_->sequence == sequence;
  auto asked = std::find_if(held_.begin(), held_.end(),
                            [&](const Waiting& w) { return w.sequence == sequence; });
  std::optional<Waiting> answered;
  if (answers_on_bus) {
    answered = on_bus_;
  } else if (asked != held_.end()) {
    // A newer request was answered first: the one on the bus got none.
    on_bus_.reset();
    asked = release_older(asked);
  }
  if (f.stick_code) {
    coded(f, time, offset, answers_on_bus ? held_.end() : asked);
    return;
  }
  Release r;
  r.kind = Release::Kind::Reply;
  r.rtu = f.rtu();
  r.time = time;
  r.offset = offset;
  r.sequence = sequence;
  r.serial = f.header.serial;
  if (!answers_on_bus && asked != held_.end()) {
    hand_on(*asked);
    answered = *asked;
    held_.erase(asked);
  }
  if (answered) {
    r.answers_request = true;
    r.late = answered->number + 1 != requests_;
    if (r.late) ++counts_.replies_after_next_request;
    on_bus_.reset();
  } else {
    ++counts_.unpaired_replies;
  }
  sink_.release(r);
}

// 05: the request got no reply from the bus. 06 with a serial other than the one a held
// request named: the stick refused a request that was not for it, and nothing reached its
// bus. Any other code is passed on as a code, and the request waits on as if none had come.
void SolarmanV5Pairing::coded(const Frame& f, double time, std::uint64_t offset,
                              std::vector<Waiting>::iterator asked) {
  Release r;
  r.kind = Release::Kind::Code;
  r.time = time;
  r.offset = offset;
  r.sequence = client_sequence(f.header);
  r.serial = f.header.serial;
  r.code = *f.stick_code;
  const bool on_bus = on_bus_ && on_bus_->sequence == r.sequence;
  const bool held = asked != held_.end();
  if (r.code == stick_code::kNoReply && (on_bus || held)) {
    r.kind = Release::Kind::NoReply;
    ++counts_.stick_timeouts;
    if (held) {
      hand_on(*asked);
      held_.erase(asked);
    }
    on_bus_.reset();
  } else if (r.code == stick_code::kWrongSerial && held && asked->serial != r.serial) {
    r.kind = Release::Kind::Refused;
    r.addressed_serial = asked->serial;
    r.request_offset = asked->offset;
    ++counts_.refused_requests;
    held_.erase(asked);
  } else {
    ++counts_.other_codes;
  }
  sink_.release(r);
}

void SolarmanV5Pairing::advance(double now) {
  if (on_bus_ && now >= due(*on_bus_)) on_bus_.reset();
  // Held oldest first: the ones whose wait ran out are a prefix.
  auto it = held_.begin();
  while (it != held_.end() && now >= due(*it)) {
    hand_on(*it);
    ++it;
  }
  held_.erase(held_.begin(), it);
}

double SolarmanV5Pairing::due(const Waiting& w) const {
  return std::nextafter(w.time + timeout_, std::numeric_limits<double>::infinity());
}

void SolarmanV5Pairing::idle(double now) {
  advance(now);
  promote();
}

std::optional<double> SolarmanV5Pairing::next_deadline() const {
  if (held_.empty()) return std::nullopt;
  // The request on the bus ending its wait lets the next held one on (promote).
  if (on_bus_) return std::min(due(*on_bus_), due(held_.front()));
  return due(held_.front());
}

void SolarmanV5Pairing::finish() {
  for (const Waiting& w : held_) hand_on(w);
  held_.clear();
  on_bus_.reset();
}

void SolarmanV5Pairing::add_counts(Totals& into) const {
  into.stick_timeouts += counts_.stick_timeouts;
  into.refused_requests += counts_.refused_requests;
  into.other_codes += counts_.other_codes;
  into.replies_after_next_request += counts_.replies_after_next_request;
  into.unpaired_replies += counts_.unpaired_replies;
}

std::string no_reply_reason(std::uint8_t code) {
  constexpr char kHex[] = "0123456789abcdef";
  std::string text = "the stick answered code ";
  text += kHex[code >> 4];
  text += kHex[code & 0x0F];
  return text;
}

std::string describe_refusal(std::uint32_t addressed, std::uint32_t stick) {
  return "the client addressed logger " + std::to_string(addressed) + "; the stick is " +
         std::to_string(stick);
}

}  // namespace pvtap::solarman_v5
