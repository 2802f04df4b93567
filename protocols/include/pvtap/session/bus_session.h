// One bus followed from raw bytes to findings: reassembly, parsing, pairing, decoding, timing.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "pvtap/codec/frame.h"
#include "pvtap/codec/frame_codec.h"
#include "pvtap/framing/stream_reassembler.h"
#include "pvtap/matching/match_events.h"
#include "pvtap/matching/request_rules.h"
#include "pvtap/matching/transaction_matcher.h"
#include "pvtap/registers/register_decoder.h"
#include "pvtap/session/bus_report.h"

namespace pvtap {

class EventTally;

// BusSessionOptions: how a session reads its input and what it works out per frame.
struct BusSessionOptions {
  ReassemblerOptions reassembler;
  MatcherConfig matcher;
  // False for inputs without timestamps (a plain byte dump): no latency, periods or timing.
  bool has_timestamps = true;
  // Why the source's timestamps cannot time the bus, when the caller knows better than the
  // reassembler (set reassembler.timestamps = Untrusted with it).
  std::string timestamp_note;
  // What vouches for the timestamps when the caller knows (a logic analyzer's sample clock),
  // for the report's timing section.
  std::string timestamp_source;
  // Decode register values of every frame for the sink (output); the latest-value table of
  // the report is kept either way.
  bool decode_values = true;
  // Feed the register inference of every polled block with words no map names (the report's
  // inferred blocks): one look-up per reply, and the statistics of those blocks' words.
  bool infer_registers = false;
};

// SessionFrame: one frame with everything the session learned about it. Valid only during
// the callback (spans and pointers point into the session).
struct SessionFrame {
  std::uint64_t id = 0;      // frames of a session are numbered from 0 in bus order
  std::uint64_t offset = 0;  // position in its direction's byte stream
  std::span<const std::uint8_t> bytes;
  Direction direction = Direction::Unknown;
  double start_time = 0;
  double end_time = 0;
  Dialect dialect = kDefaultDialect;  // GSL or plain Modbus as its station speaks
                                      // (dialects/modbus/station_dialects.h)
  // The dialect its station spoke until this frame, when this frame says it changed.
  std::optional<Dialect> dialect_changed_from;
  Role role = Role::Request;  // as corrected by the matcher (echoed writes)
  FrameCheck check;
  const Frame* frame = nullptr;  // null when the bytes do not parse (see parse_error)
  // The station it is counted under (station_rule.h); nullopt for a damaged frame paired with
  // no good frame (yet: a damaged request waits for its reply or its timeout).
  std::optional<std::uint8_t> station;
  std::string_view parse_error;
  // Replies: the request answered, and the latency (when the input has timestamps).
  std::optional<std::uint64_t> request_id;
  std::optional<double> latency;
  ReplyKind reply_kind = ReplyKind::Normal;
  bool broadcast_answer = false;
  bool unsolicited = false;
  std::optional<double> late_by;  // unsolicited, but fits a timed-out request this much later
  std::optional<std::uint64_t> late_for;  // ... that request
  bool duplicate = false;
  // A second reply to one request whose bytes differ from the first's: two devices answer to
  // this address. Not also a duplicate.
  bool address_conflict = false;
  std::optional<double> conflict_after;  // from its request's end (with timestamps), seconds
  // The request a duplicate or a conflicting reply answered before.
  std::optional<std::uint64_t> duplicate_of;
  bool role_corrected = false;
  // A request repeated byte for byte as soon as it ended (EchoedRequest): the tap's adapter's
  // echo of echo_of. Counted as an echo only, not as a request of its station.
  bool echo = false;
  std::optional<std::uint64_t> echo_of;
  std::optional<ByteCountMismatch> count_mismatch;
  // A request with a good check asking for a quantity its function does not allow.
  std::optional<QuantityProblem> quantity_problem;
  // A request with a good check to address 0 that may not be broadcast (a read): no station
  // answers it (broadcast_not_allowed).
  bool broadcast_not_allowed = false;
  // A write with a good check whose byte count disagrees with its quantity.
  std::optional<WriteCountProblem> write_count_problem;
  // The request whose start address places this reply's words (its own, or the one it
  // duplicates), when that request's check was good. Values are decoded only from a frame
  // with a good check, and never placed by a request with a bad one.
  std::optional<std::uint64_t> placed_by;
  const Frame* placing_request = nullptr;  // that request's frame (coil_bits places by it)
  // The register map its station's values are read with (its own, or its dialect's): it also
  // names the station's coils and inputs (coil_def).
  const RegisterMap* map = nullptr;
  bool values_trusted = false;  // a good check: its values may be decoded
  DecodeReport decode;
  std::span<const DecodedValue> values;  // empty unless options.decode_values
};

// UnansweredKind: how a request without a reply is judged.
enum class UnansweredKind : std::uint8_t {
  Timeout = 0,     // a finding: no reply within the timeout, or the next request came first
  InputEnded = 1,  // the input ended before its timeout ran out: not a finding
  AfterLoss = 2,   // capture data was lost while it waited: the reply may be in the gap
  // The request had a bad check: the slave was right to ignore it (not the slave's finding).
  DamagedRequest = 3,
};

// SessionTimeout: a request that got no reply.
struct SessionTimeout {
  Timeout timeout;
  UnansweredKind kind = UnansweredKind::Timeout;
  std::optional<std::uint8_t> station;  // the station it is counted under (station_rule.h)
  double request_start = 0;
  double request_end = 0;
  double time = 0;  // when it was given up: request_end + timeout.waited
};

// SessionCollision: two transmissions at once on a bus of more than one master
// (session/collision_tally.h). Named once the bus has shown its second master: at its first
// trace, or, for the collisions that came before that evidence, when it came.
struct SessionCollision {
  double start_time = 0;  // its first trace's first byte
  double end_time = 0;    // its first trace's last byte (more traces may follow)
  bool late = false;      // named after the fact, when the second master showed
};

// SessionGap: capture data lost in one direction (the bytes around it are not joined).
struct SessionGap {
  Direction direction = Direction::Unknown;
  double time = 0;
  std::optional<std::uint64_t> lost_bytes;  // when the capture path knows it
};

// SessionNoise: bytes that belong to no frame. Valid only during the callback.
struct SessionNoise {
  NoiseEvent noise;
  Direction direction = Direction::Unknown;
};

// LineErrorKind: why the UART could not read a character cleanly.
enum class LineErrorKind : std::uint8_t { Framing, Parity, FramingAndParity, Break };

// SessionLineError: a character the UART reading the bus's line from its samples could not
// read cleanly (a stop bit read as space, a parity bit that does not hold) or a break. Such a
// character still goes to its frame, whose check then fails; the event says which and why.
struct SessionLineError {
  double time = 0;  // its start bit's edge
  double duration = 0;
  std::uint8_t value = 0;  // none for a break
  LineErrorKind kind = LineErrorKind::Framing;
  Direction direction = Direction::Unknown;  // the side of a bus on two channels
};

// SessionDriverGlitch: a byte an RS485 driver put on the line as it switched on (right before
// a frame) or off (right after one); kept out of the frames and of the noise.
struct SessionDriverGlitch {
  double time = 0;  // its start bit's edge
  std::uint8_t value = 0;
  bool switch_on = true;
  bool framing_error = false;
  bool parity_error = false;
  Direction direction = Direction::Unknown;
};

// BusSessionSink: receives a session's events in bus order. All default to doing nothing.
class BusSessionSink {
 public:
  virtual ~BusSessionSink() = default;
  virtual void on_frame(const SessionFrame&) {}
  virtual void on_timeout(const SessionTimeout&) {}
  virtual void on_noise(const SessionNoise&) {}
  virtual void on_gap(const SessionGap&) {}
  virtual void on_collision(const SessionCollision&) {}
  virtual void on_line_error(const SessionLineError&) {}
  virtual void on_driver_glitch(const SessionDriverGlitch&) {}
};

// BusSession: the core's whole pipeline for one half-duplex bus, with no I/O of its own.
//
// Chunks with a known direction (a gateway's two TCP directions) are reassembled per
// direction, so that a loss in one direction does not break frames of the other; chunks of
// unknown direction (a tap on the bus) share one stream. Frames go to the transaction matcher
// in the order they are found; its findings, the frame's decoded values and its timing come
// back to the sink as one SessionFrame. Memory is bounded by the number of stations and
// registers seen, not by the length of the input.
class BusSession {
 public:
  BusSession(BusSessionOptions options, const RegisterDecoder& decoder, BusSessionSink& sink);
  ~BusSession();
  BusSession(const BusSession&) = delete;
  BusSession& operator=(const BusSession&) = delete;

  // Half duplex: a chunk of known direction after one of the other known direction ends the
  // other's turn (end_turn), unless the chunk says that turn is not complete.
  void feed(const BusChunk& chunk);
  // A frame or noise run an earlier run decided (StreamReassembler::feed_decided), in the
  // stream of `piece.direction`; ends the other direction's turn as feed does.
  void feed_decided(const DecidedPiece& piece);
  // A frame a carrier delivered whole and without a check of its own (a Modbus/TCP ADU):
  // `frame` is its station byte and PDU, at `offset` in `direction`'s stream, sent at `time`.
  // It bypasses the reassembler; its check says the carrier vouched for it (FrameCheck). Its
  // dialect is the one whose length rules its bytes fit (Hybrid, or GSL/Modbus). A reply the
  // carrier paired with the last request to its station (`answers_request`: Modbus/TCP's
  // transaction id) answers it however late it comes.
  void carried_frame(Direction direction, std::uint64_t offset, std::span<const std::uint8_t> frame,
                     double time, bool answers_request = false);
  // A whole RTU frame a carrier delivered with its check (a logger stick's V5 frame pins both
  // its ends): fed, and its turn ended at once. `answers_request`: the carrier paired this
  // reply with the request it fed just before (the stick echoed the request's sequence byte),
  // so it answers that request however late it comes.
  void whole_frame(const BusChunk& chunk, bool answers_request = false);
  // The carrier answered the last request fed with `code` in place of a reply (a logger
  // stick's 05): no reply came from the bus, a timeout for that reason at `time`.
  void carrier_no_reply(double time, std::uint8_t code);
  // The sender in `direction` has finished its turn: on a half-duplex bus the other side
  // started talking, so its pending bytes are complete. Call it only when no data of that
  // direction is still on its way (e.g. no TCP segment missing).
  void end_turn(Direction direction);
  // What the UART reading the bus's line saw besides its bytes (a logic recording): counted
  // and handed on as every other event is.
  void line_error(const SessionLineError& e);
  void driver_glitch(const SessionDriverGlitch& g);
  // Capture data of `direction` was lost at `time`; reported as a gap.
  void data_lost(Direction direction, double time, std::optional<std::uint64_t> lost_bytes);
  // The byte stream restarts (a new TCP connection to the same gateway); nothing was lost.
  // The next chunk starts a turn of its own: it ends no turn of the previous stream.
  void restart(Direction direction);
  // The bus has been silent until `now` (live capture): pending decisions and timeouts.
  void idle(double now);
  // When idle() can next decide something (see StreamReassembler::next_deadline and
  // TransactionMatcher::next_deadline); nullopt when only more bytes can.
  std::optional<double> next_deadline() const;
  // End of input: every byte is decided, every waiting request judged.
  void finish();

  BusReport report() const;
  // The report's masters, collisions and echoes alone (their timing is the costly part).
  BusSharing sharing() const;
  ReassemblerTotals totals() const;  // of all directions so far
  // The counts of this bus's events so far, by the rules of the report; brought up to date
  // before an event reaches the sink.
  const EventTally& tally() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  void turn_of(Direction direction, bool previous_turn_complete);
};

}  // namespace pvtap
