// MbapFlow: one Modbus/TCP connection read into a bus session, ADU by ADU.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "pvtap/carriers/mbap_pairing.h"
#include "pvtap/carriers/mbap_reader.h"
#include "pvtap/session/bus_session.h"

namespace pvtap {

// MbapFlow: a reader per direction, the pairing by transaction id, and the session that
// gets the unit id and PDU of every ADU as a frame (BusSession::carried_frame). The MBAP
// header bytes are the carrier's; the headers that lied are findings kept here.
class MbapFlow final : MbapReleaseSink {
 public:
  static constexpr std::size_t kMaxExamples = 5;

  // `timeout`: the session's matcher timeout. A gateway answers every request it got (with
  // 0x0B at worst, after a serial timeout of its own that may be longer than pvtap's), so a
  // request is held for its reply ten times as long (10 s at least); one handed on alone
  // after that, or at the end of the flow, is judged by the matcher as unanswered.
  MbapFlow(BusSession& bus, double timeout);

  void feed(Direction d, std::span<const std::uint8_t> bytes, double time);
  // Data of `d` was lost: its unfinished ADU is given up; the session is told by the caller.
  void data_lost(Direction d, double time);
  void finish(double time);
  // Nothing arrived until `now` (a live capture): requests held past their wait are handed on.
  void idle(double now) { pairing_.advance(now); }
  // When idle() can next hand a request on (MbapPairing::next_deadline).
  std::optional<double> next_deadline() const { return pairing_.next_deadline(); }

  MbapTotals totals() const;  // of both directions
  // Stream position of the next byte of `d`: the offset its next ADU's frame will have.
  std::uint64_t position(Direction d) const;
  const std::vector<MbapFinding>& finding_examples() const { return examples_; }

 private:
  struct DirectionReader final : MbapSink {
    DirectionReader(MbapFlow& f, Direction d) : flow(f), direction(d), reader(*this) {}
    void on_adu(const MbapAdu& adu) override;
    void on_finding(const MbapFinding& finding) override;
    MbapFlow& flow;
    Direction direction;
    MbapReader reader;
  };
  void release(const MbapRelease& r) override;

  BusSession& bus_;
  MbapPairing pairing_;
  DirectionReader requests_;
  DirectionReader replies_;
  std::vector<MbapFinding> examples_;
};

// What a finding says, for reports: "protocol id 1, not 0: 24 bytes skipped".
std::string describe(const MbapFinding& f);

}  // namespace pvtap
