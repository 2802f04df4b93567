// MbapReader: one direction of a Modbus/TCP flow cut into ADUs, accounting for every byte.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace pvtap {

// The MBAP header: transaction id, protocol id and length (u16 big-endian each), unit id.
inline constexpr std::size_t kMbapHeaderBytes = 7;
// The bytes before the unit id: the carrier's own. The unit id and the PDU are the frame as a
// serial bus carries it, less its CRC.
inline constexpr std::size_t kMbapCarrierBytes = 6;
// The length counts the unit id and the PDU: a function code at least, a 253-byte PDU at most.
inline constexpr std::uint16_t kMbapMinLength = 2;
inline constexpr std::uint16_t kMbapMaxLength = 254;

// MbapAdu: one ADU. `frame` (unit id + PDU) is valid only during the callback.
struct MbapAdu {
  std::uint64_t offset = 0;  // stream position of its first header byte
  std::uint16_t transaction = 0;
  std::uint8_t unit = 0;
  std::span<const std::uint8_t> frame;
  double time = 0;  // of the chunk that completed it
};

// MbapProblem: why a header cannot be believed.
enum class MbapProblem : std::uint8_t {
  ProtocolId,      // not 0: not Modbus
  LengthTooShort,  // under 2: no function code
  LengthTooLong,   // over 254: longer than any ADU
  LengthOverruns,  // more than was sent: the next segment is whole ADUs of its own
  Truncated,       // the flow ended or lost data inside an ADU
};

// MbapFinding: a header that lied, and the bytes given up for it.
struct MbapFinding {
  std::uint64_t offset = 0;
  MbapProblem problem = MbapProblem::ProtocolId;
  std::uint16_t protocol_id = 0;
  std::uint16_t declared_length = 0;
  std::uint64_t skipped = 0;  // bytes given up, header included
  double time = 0;
};

// MbapTotals: bytes_in == carrier_bytes + frame_bytes + skipped_bytes + pending.
struct MbapTotals {
  std::uint64_t bytes_in = 0;
  std::uint64_t adus = 0;
  std::uint64_t carrier_bytes = 0;  // 6 per ADU
  std::uint64_t frame_bytes = 0;    // unit ids and PDUs
  std::uint64_t skipped_bytes = 0;  // given up in findings
  std::uint64_t findings = 0;
  MbapTotals& operator+=(const MbapTotals& o);
};

class MbapSink {
 public:
  virtual ~MbapSink() = default;
  virtual void on_adu(const MbapAdu& adu) = 0;
  virtual void on_finding(const MbapFinding& finding) = 0;
};

// MbapReader: fed one direction of a TCP flow in the pieces it arrived in (an ADU may span
// pieces, a piece may hold several).
//
// Resynchronisation: TCP gives no marker to find a header again, but clients and gateways
// write one ADU (or a run of them) per send, so a piece normally starts with a header.
//   - A header that cannot be true (protocol id not 0, length under 2 or over 254) gives up
//     the rest of its piece; reading resumes at the next piece.
//   - A length that runs past its piece is believed (TCP may split an ADU) unless the next
//     piece is, by itself, a run of whole ADUs: then the length lied, the short ADU is given
//     up and reading resumes at that piece.
//   - Data lost (discontinuity) or the end of the flow gives up an unfinished ADU.
class MbapReader {
 public:
  explicit MbapReader(MbapSink& sink);

  void feed(std::span<const std::uint8_t> bytes, double time);
  void discontinuity(double time);
  void finish(double time);

  const MbapTotals& totals() const { return totals_; }
  std::uint64_t pending_bytes() const { return buffer_.size() - read_; }

 private:
  bool read_one(std::size_t piece_start, double time);
  void give_up(std::size_t to, MbapProblem problem, double time);

  MbapSink& sink_;
  std::vector<std::uint8_t> buffer_;  // unread bytes; buffer_[0] is at stream base_
  std::size_t read_ = 0;
  std::uint64_t base_ = 0;
  MbapTotals totals_;
};

}  // namespace pvtap
