// MbapPairing: transactions handed on whole, by transaction id, in the order replies came.
#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <vector>

#include "pvtap/carriers/mbap_pairing.h"

namespace pvtap {
namespace {

struct Recorder : MbapReleaseSink {
  void release(const MbapRelease& r) override {
    std::string s = r.direction == Direction::ToSlave ? "req" : "rep";
    s += std::to_string(r.transaction);
    order.push_back(s);
  }
  std::vector<std::string> order;
};

const std::uint8_t kFrame[] = {1, 3, 0, 0, 0, 1};

MbapAdu adu(std::uint16_t tid, double time) {
  return MbapAdu{0, tid, 1, kFrame, time};
}

TEST(MbapPairing, PipelinedRequestsAreHandedOnWithTheirOwnReplies) {
  Recorder rec;
  MbapPairing pairing(1.0, rec);
  pairing.request(adu(1, 0.00));
  pairing.request(adu(2, 0.01));
  pairing.request(adu(3, 0.02));
  EXPECT_TRUE(rec.order.empty());
  pairing.reply(adu(2, 0.05));  // out of order
  pairing.reply(adu(1, 0.06));
  pairing.reply(adu(3, 0.07));
  EXPECT_EQ(rec.order, (std::vector<std::string>{"req2", "rep2", "req1", "rep1", "req3", "rep3"}));
  EXPECT_EQ(pairing.held(), 0u);
}

TEST(MbapPairing, AnUnansweredRequestIsHandedOnAloneAfterItsTimeout) {
  Recorder rec;
  MbapPairing pairing(1.0, rec);
  pairing.request(adu(1, 0.0));
  pairing.request(adu(2, 0.5));
  pairing.reply(adu(2, 0.6));
  EXPECT_EQ(rec.order, (std::vector<std::string>{"req2", "rep2"}));
  pairing.advance(1.01);
  EXPECT_EQ(rec.order, (std::vector<std::string>{"req2", "rep2", "req1"}));
}

// A live capture wakes at the deadline the pairing gives: the held request goes then, not
// before and not a wake later.
TEST(MbapPairing, AHeldRequestGoesAtItsDeadline) {
  Recorder rec;
  MbapPairing pairing(1.0, rec);
  EXPECT_FALSE(pairing.next_deadline().has_value());
  pairing.request(adu(1, 2.0));
  pairing.request(adu(2, 2.5));
  const std::optional<double> due = pairing.next_deadline();
  ASSERT_TRUE(due.has_value());
  EXPECT_GT(*due, 3.0);
  EXPECT_LT(*due, 3.0 + 1e-9);
  pairing.advance(3.0);
  EXPECT_TRUE(rec.order.empty());
  pairing.advance(*due);
  EXPECT_EQ(rec.order, (std::vector<std::string>{"req1"}));
  ASSERT_TRUE(pairing.next_deadline().has_value());
  EXPECT_GT(*pairing.next_deadline(), 3.5);
}

TEST(MbapPairing, AReplyNobodyWaitsForAndAReusedIdAndTheEnd) {
  Recorder rec;
  MbapPairing pairing(1.0, rec);
  pairing.reply(adu(7, 0.0));
  pairing.request(adu(1, 0.1));
  pairing.request(adu(1, 0.2));  // reuses the id: the first waits no more
  pairing.finish();
  EXPECT_EQ(rec.order, (std::vector<std::string>{"rep7", "req1", "req1"}));
}

}  // namespace
}  // namespace pvtap
