// BusSession::Impl: the state of one bus session, shared by its event handling
// (bus_session.cpp) and its report (bus_session_report.cpp).
#pragma once

#include "pvtap/session/bus_session.h"

#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "dialects/dialect_module.h"
#include "dialects/modbus/station_dialects.h"
#include "pvtap/statistics/bus_timing.h"
#include "session/bus_tally.h"
#include "session/collision_tally.h"
#include "session/reply_values.h"
#include "session/session_times.h"

namespace pvtap {

struct BusSession::Impl {
  // DirectionStream: the reassembler of one direction and where its events go.
  struct DirectionStream : ReassemblerSink {
    DirectionStream(Impl& o, Direction d)
        : owner(o), direction(d), reassembler(o.options.reassembler, *this) {}
    void on_frame(const FrameEvent& e) override { owner.on_frame(direction, e); }
    void on_noise(const NoiseEvent& e) override {
      const SessionNoise noise{e, direction};
      owner.tally.add_noise(noise);
      if (owner.options.has_timestamps) owner.collisions.add_damage(e.start_time, e.end_time);
      owner.sink.on_noise(noise);
      owner.name_collisions(false);
    }

    Impl& owner;
    Direction direction;
    StreamReassembler reassembler;
    double last_feed_time = -std::numeric_limits<double>::infinity();
  };

  Impl(BusSessionOptions o, const RegisterDecoder& d, BusSessionSink& s)
      : options(o),
        sink(s),
        matcher(matcher_config(o)),
        times(options),
        replies(d, options),
        collisions(BusTiming(o.reassembler.baud, o.reassembler.bits_per_char).t35,
                   o.matcher.timeout),
        station_dialects(o.reassembler.dialects, d),
        decoder(d) {}

  // Echoes are told by time: a copy within 3.5 characters, where no slave may answer yet
  // (one for a write whose reply is the same bytes).
  // Batched timestamps (a USB adapter's) do not judge silences, but the bytes of one batch
  // are placed back to back, and an echo comes in its request's batch.
  static MatcherConfig matcher_config(const BusSessionOptions& o) {
    MatcherConfig config = o.matcher;
    config.timed = o.has_timestamps;
    if (!config.echo_within && o.has_timestamps) {
      const BusTiming timing(o.reassembler.baud, o.reassembler.bits_per_char);
      config.echo_within = timing.t35;
      config.echoing_reply_within = timing.char_time;
    }
    return config;
  }

  DirectionStream& stream(Direction d) {
    auto& slot = streams[index_of(d)];
    if (!slot) slot = std::make_unique<DirectionStream>(*this, d);
    return *slot;
  }

  // A reply that may also read as the Modbus family's (Hybrid's), to a station last asked in
  // the Modbus family, is read again (a Hybrid station's replies cost one table look-up).
  void on_frame(Direction direction, const FrameEvent& e) {
    if (!detail::dialect_module(e.dialect).reply_may_be_modbus_family || e.role != Role::Response ||
        e.bytes.empty() || !asked_in_modbus_family(e.bytes[0])) {
      on_frame(direction, e, e.bytes);
      return;
    }
    FrameEvent asked = e;
    asked.dialect = reply_dialect(e.bytes, e.role, asked_dialect(e.bytes[0]), e.dialect);
    on_frame(direction, asked, e.bytes);
  }
  bool asked_in_modbus_family(std::uint8_t station) const {
    const auto asked = asked_dialect(station);
    return asked && modbus_family(*asked);
  }
  // The dialect of the last request with a good check to `station` (request_dialects).
  std::optional<Dialect> asked_dialect(std::uint8_t station) const {
    if (request_dialects[station] == 0) return std::nullopt;
    return static_cast<Dialect>(request_dialects[station] - 1);
  }
  Dialect reply_dialect(std::span<const std::uint8_t> wire, Role role, std::optional<Dialect> asked,
                        Dialect fallback) const;
  // `wire` is what the codec parses: the frame's bytes, with a check appended when the
  // carrier took it away.
  void on_frame(Direction direction, const FrameEvent& e, std::span<const std::uint8_t> wire);
  void handle_parsed(SessionFrame& out, const FrameEvent& e, std::uint32_t content);
  void note_for_collisions(const SessionFrame& out);
  // The collisions the bus has shown so far (`at_end`: over the whole input), to the sink.
  void name_collisions(bool at_end);
  // Timeouts come before the frame that made them due.
  void report(std::span<const Timeout> timeouts) {
    for (const Timeout& t : timeouts) report(t);
  }
  void report(const Timeout& t);
  TimestampQuality timestamp_quality() const;
  ReassemblerTotals totals() const;
  BusSharing sharing(const TimingReport& timing) const;

  BusSessionOptions options;
  BusSessionSink& sink;
  std::array<std::unique_ptr<DirectionStream>, kDirections> streams;
  TransactionMatcher matcher;
  detail::SessionTimes times;
  detail::ReplyValues replies;
  detail::BusTally tally;
  detail::CollisionTally collisions;
  detail::StationDialects station_dialects;
  const RegisterDecoder& decoder;
  // Each dialect's map as the decoder gives it, looked up at its first frame: a per-frame
  // lookup would cost the built-in map's once-only guard every time.
  std::array<const RegisterMap*, kDialectCount> dialect_maps{};
  Frame frame;                // the frame being handled; SessionFrame::frame points here
  ReassemblerTotals carried;  // frames delivered whole by a carrier (carried_frame)
  std::vector<std::uint8_t> carried_wire;  // a carried frame with the CRC the codec expects
  bool answers_pending = false;            // the carried reply being handled was paired
  // The station of the last request the matcher took (a carrier's code may answer it).
  std::optional<std::uint8_t> last_request_station;
  // The dialect of the last request with a good check to each station, plus one (0: none yet):
  // a reply whose bytes read alike in two dialects (Hybrid and Modbus share 0x11 and 0x17)
  // takes its request's, failing that its station's history.
  std::array<std::uint8_t, 256> request_dialects{};
  std::uint64_t next_id = 0;
  std::uint64_t loss_boundary_id = 0;  // requests before this id were waiting during a loss
  Direction last_direction = Direction::Unknown;  // of the last chunk fed
};

}  // namespace pvtap
