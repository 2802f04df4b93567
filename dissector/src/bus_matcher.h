// BusMatcher: pairs the frames of one bus during the first pass, writing into their records.
#pragma once

#include <cstdint>
#include <vector>

#include "frame_record.h"
#include "pvtap/frame_summary.h"
#include "pvtap/transaction_matcher.h"

namespace pvtap::dissector {

// One per bus: a TCP connection, a UDP flow, or the records of a capture file. It sees the
// frames in capture order, which Wireshark guarantees only on the first pass.
class BusMatcher final : public MatchSink {
 public:
  explicit BusMatcher(MatcherConfig config);

  // Feeds one frame; fills the matching fields of `record` and of the records it pairs with.
  void observe(FrameRecord& record, const FrameSummary& summary, bool role_known);

 private:
  void on_transaction(const Transaction& t) override;
  void on_timeout(const Timeout& t) override;
  void on_unsolicited(const UnsolicitedReply& u) override;
  void on_duplicate(const DuplicateReply& d) override;
  void on_byte_count_mismatch(const ByteCountMismatch& m) override;
  void on_role_corrected(const RoleCorrection& c) override;
  FrameRecord* at(std::uint64_t id) const;

  TransactionMatcher matcher_;
  std::vector<FrameRecord*> records_;  // by frame id
  nstime_t origin_{};
};

// A matcher that lives until the capture file is closed.
BusMatcher* new_bus_matcher(double reply_timeout_seconds);

// Frees every matcher; registered as a cleanup routine.
void release_bus_matchers();

}  // namespace pvtap::dissector
