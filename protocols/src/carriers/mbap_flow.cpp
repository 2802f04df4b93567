#include "pvtap/carriers/mbap_flow.h"

#include <algorithm>

namespace pvtap {

MbapFlow::MbapFlow(BusSession& bus, double timeout)
    : bus_(bus),
      pairing_(std::max(10 * timeout, 10.0), *this),
      requests_(*this, Direction::ToSlave),
      replies_(*this, Direction::FromSlave) {}

void MbapFlow::DirectionReader::on_adu(const MbapAdu& adu) {
  if (direction == Direction::ToSlave) {
    flow.pairing_.request(adu);
  } else {
    flow.pairing_.reply(adu);
  }
}

void MbapFlow::DirectionReader::on_finding(const MbapFinding& finding) {
  if (flow.examples_.size() < kMaxExamples) flow.examples_.push_back(finding);
}

void MbapFlow::release(const MbapRelease& r) {
  bus_.carried_frame(r.direction, r.offset, r.frame, r.time, r.answers_request);
}

void MbapFlow::feed(Direction d, std::span<const std::uint8_t> bytes, double time) {
  (d == Direction::FromSlave ? replies_ : requests_).reader.feed(bytes, time);
}

void MbapFlow::data_lost(Direction d, double time) {
  (d == Direction::FromSlave ? replies_ : requests_).reader.discontinuity(time);
}

void MbapFlow::finish(double time) {
  requests_.reader.finish(time);
  replies_.reader.finish(time);
  pairing_.finish();
}

std::uint64_t MbapFlow::position(Direction d) const {
  return (d == Direction::FromSlave ? replies_ : requests_).reader.totals().bytes_in;
}

MbapTotals MbapFlow::totals() const {
  MbapTotals t = requests_.reader.totals();
  t += replies_.reader.totals();
  return t;
}

namespace {
std::string_view problem_text(MbapProblem p) {
  switch (p) {
    case MbapProblem::ProtocolId:
      return "protocol id not 0";
    case MbapProblem::LengthTooShort:
      return "length too short for a PDU";
    case MbapProblem::LengthTooLong:
      return "length longer than any ADU";
    case MbapProblem::LengthOverruns:
      return "length overruns what was sent (the next segment is whole ADUs)";
    case MbapProblem::Truncated:
      return "ADU cut short (the flow ended or lost data)";
  }
  return "?";
}
}  // namespace

std::string describe(const MbapFinding& f) {
  std::string s = "MBAP ";
  s += problem_text(f.problem);
  s += " (protocol id " + std::to_string(f.protocol_id) + ", length " +
       std::to_string(f.declared_length) + "): " + std::to_string(f.skipped) +
       " bytes skipped at offset " + std::to_string(f.offset);
  return s;
}

}  // namespace pvtap
