// SolarmanV5Pairing: a logger stick's responses paired with the client's requests by the
// sequence byte the stick echoes, and the stick's codes read as what they answer.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "pvtap/carriers/solarman_v5_frame.h"
#include "pvtap/carriers/solarman_v5_reader.h"

namespace pvtap::solarman_v5 {

// Release: what the pairing hands on, in the order the bus behind the stick saw it.
struct Release {
  enum class Kind : std::uint8_t {
    Request,  // an RTU request, for the bus
    Reply,    // an RTU reply
    NoReply,  // code 05: the last request handed on got no reply from the bus
    Refused,  // code 06 to a request naming another serial: the request never reached a bus
    Code,     // any other code, or a code that answers no request waiting: only a code
  };
  Kind kind = Kind::Request;
  std::span<const std::uint8_t> rtu;  // Request, Reply: valid only during the callback
  double time = 0;                    // of the frame's V5 frame
  std::uint64_t offset = 0;           // of that V5 frame in its direction's stream
  std::uint8_t sequence = 0;          // the sequence byte the client chose (and the stick echoes)
  std::uint32_t serial = 0;           // the logger serial in the frame's header
  // Reply: it answers the last request handed on (the one whose sequence byte it echoes).
  bool answers_request = false;
  bool late = false;  // Reply: the client had sent a newer request before it came
  std::uint8_t code = 0;
  std::uint32_t addressed_serial = 0;  // Refused: the serial the client's request named
  std::uint64_t request_offset = 0;    // Refused: the offset of the refused request's V5 frame
};

class ReleaseSink {
 public:
  virtual ~ReleaseSink() = default;
  virtual void release(const Release& r) = 0;
};

// SolarmanV5Pairing: the stick echoes each request's sequence byte in its response, and a
// real stick may send a heartbeat where the reply was due and the reply after the client's
// next request. Pairing by order would then shift every later pair; here the sequence byte
// pairs them, and the bus matcher is handed each transaction in bus order.
//
// A request to the stick's own serial (known from its frames) is handed on at once when no
// other request waits: the usual case, one request at a time. One that comes while another
// waits is held (the bus behind the stick is half duplex: it goes on the bus after the one
// before), and so is one naming another serial (the stick may refuse it) until the stick
// says. A waiting request stops waiting when the response with its sequence byte comes (a
// reply is handed on right after it), when a newer request's response comes first, when its
// wait runs out (`timeout`, the matcher's: a reply after that is a late reply to it), when a
// newer request reuses its sequence byte, or at the end. A reply whose sequence byte no
// waiting request has is handed on alone for the matcher to judge. A response carrying a
// stick code answers its request as the code says.
class SolarmanV5Pairing {
 public:
  SolarmanV5Pairing(double timeout, ReleaseSink& sink);

  // A frame of the flow at `offset` of its direction's stream: requests and responses are
  // paired, the stick's frames name its serial, and every frame moves time on.
  void frame(const Frame& f, double time, std::uint64_t offset = 0);
  // Time has reached `now`: requests whose wait ran out stop waiting.
  void advance(double now);
  // Nothing arrived until `now` (a live capture): what a frame at `now` would release, before
  // what it carries: requests whose wait ran out, and the next held one on the bus.
  void idle(double now);
  // When idle() next releases a held request; nullopt while none is held.
  std::optional<double> next_deadline() const;
  // The flow ended: every held request is handed on.
  void finish();

  // Adds what the pairing counted (stick codes by meaning, late and unpaired replies).
  void add_counts(Totals& into) const;
  // The serial in the stick's own frames, once one came.
  std::optional<std::uint32_t> stick_serial() const { return stick_serial_; }
  std::size_t held() const { return held_.size(); }

 private:
  struct Waiting {
    std::uint64_t number = 0;  // requests are numbered in the order sent
    std::uint64_t offset = 0;
    std::uint8_t sequence = 0;
    std::uint32_t serial = 0;
    double time = 0;
    std::size_t size = 0;
    std::array<std::uint8_t, kMaxPayload> rtu{};
  };
  void request(const Frame& f, double time, std::uint64_t offset);
  void response(const Frame& f, double time, std::uint64_t offset);
  void coded(const Frame& f, double time, std::uint64_t offset,
             std::vector<Waiting>::iterator asked);
  // Hands on the held requests before `asked` alone, then removes them.
  std::vector<Waiting>::iterator release_older(std::vector<Waiting>::iterator asked);
  // While no request waits on the bus, the oldest held one goes on it (or gives up).
  void promote();
  bool for_this_stick(const Waiting& w) const { return stick_serial_ == w.serial; }
  void hand_on(const Waiting& w);
  // Past its wait, not at it; advance() and next_deadline() both compare with this value.
  double due(const Waiting& w) const;

  double timeout_;
  ReleaseSink& sink_;
  // The request handed on that waits for its response (its RTU bytes are not needed again).
  std::optional<Waiting> on_bus_;
  std::vector<Waiting> held_;  // oldest first: requests not handed on yet
  std::uint64_t requests_ = 0;
  std::optional<std::uint32_t> stick_serial_;
  Totals counts_;
};

// The stick's reason for a request without a reply: "the stick answered code 05".
std::string no_reply_reason(std::uint8_t code);
// A refusal said plainly: "the client addressed logger 2111130827; the stick is 4068039735".
std::string describe_refusal(std::uint32_t addressed, std::uint32_t stick);
// The sequence byte of a frame: the client's, echoed by the stick in its response.
inline std::uint8_t client_sequence(const Header& h) {
  return static_cast<std::uint8_t>(h.sequence & 0xFFu);
}

}  // namespace pvtap::solarman_v5
