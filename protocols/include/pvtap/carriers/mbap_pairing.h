// MbapPairing: Modbus/TCP requests paired with replies by transaction id, handed on in pairs.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "pvtap/carriers/mbap_reader.h"
#include "pvtap/framing/bus_chunk.h"

namespace pvtap {

// MbapRelease: one ADU's frame handed on. `frame` is valid only during the callback.
struct MbapRelease {
  Direction direction = Direction::Unknown;
  std::uint64_t offset = 0;  // of its MBAP header in its direction's stream
  std::uint16_t transaction = 0;
  std::span<const std::uint8_t> frame;  // unit id + PDU
  double time = 0;
  bool answers_request = false;  // a reply handed on right after the request it answers
};

class MbapReleaseSink {
 public:
  virtual ~MbapReleaseSink() = default;
  virtual void release(const MbapRelease& r) = 0;
};

// MbapPairing: the bus matcher pairs a reply with the last request to its station, in bus
// order; a Modbus/TCP client may pipeline several requests to one unit before the first
// reply. So requests are held here until the reply with their transaction id arrives, then
// the two are handed on together: the matcher sees each transaction whole and times it by
// the ADUs' own times. A request whose reply has not come `timeout` seconds after it (or
// before the flow ends, or whose transaction id a newer request reuses) is handed on alone,
// for the matcher to judge as unanswered. A reply that answers no held request is handed on
// at once (the matcher judges it unsolicited or late).
class MbapPairing {
 public:
  MbapPairing(double timeout, MbapReleaseSink& sink);

  void request(const MbapAdu& adu);
  void reply(const MbapAdu& adu);
  // Time has reached `now`: requests whose timeout ran out are handed on.
  void advance(double now);
  // When advance() next hands a request on while nothing arrives (a live capture); nullopt
  // while none is held.
  std::optional<double> next_deadline() const;
  // The flow ended: every held request is handed on.
  void finish();

  std::size_t held() const { return held_.size(); }

 private:
  struct Held {
    std::uint64_t offset = 0;
    std::uint16_t transaction = 0;
    double time = 0;
    std::uint8_t size = 0;
    std::array<std::uint8_t, kMbapMaxLength> frame{};
  };
  void hand_on(const Held& h);
  // Past its timeout, not at it; advance() and next_deadline() both compare with this value.
  double due(const Held& h) const;

  double timeout_;
  MbapReleaseSink& sink_;
  std::vector<Held> held_;  // oldest first; a client pipelines a few at most
};

}  // namespace pvtap
