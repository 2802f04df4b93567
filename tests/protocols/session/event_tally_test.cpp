// EventTally: one rule for what each session event counts as, and tallies that merge.
#include "pvtap/session/event_tally.h"

#include <gtest/gtest.h>

namespace pvtap {
namespace {

// A reply of station 3 with the given check, as the session hands it on.
SessionFrame reply(const Frame& frame, bool check_ok, ReplyKind kind) {
  SessionFrame f;
  f.frame = &frame;
  f.role = Role::Response;
  f.check.ok = check_ok;
  f.reply_kind = kind;
  return f;
}

TEST(EventTally, AnExceptionCountsOnlyWhenItsCheckHolds) {
  Frame frame;
  frame.station = 3;
  frame.function = 0x83;
  frame.exception_code = 2;
  EventTally tally;
  tally.add(reply(frame, true, ReplyKind::GslException));
  tally.add(reply(frame, false, ReplyKind::GslException));
  EXPECT_EQ(tally.counts().frames, 2u);
  EXPECT_EQ(tally.counts().exceptions, 1u);
  EXPECT_EQ(tally.counts().damaged_frames, 1u);
  EXPECT_EQ(exception_code(reply(frame, true, ReplyKind::GslException)), 2);
  EXPECT_FALSE(exception_code(reply(frame, false, ReplyKind::GslException)).has_value());
  EXPECT_FALSE(exception_code(reply(frame, true, ReplyKind::Normal)).has_value());
}

TEST(EventTally, EachUnansweredKindHasItsOwnCount) {
  EventTally tally;
  for (UnansweredKind kind :
       {UnansweredKind::Timeout, UnansweredKind::Timeout, UnansweredKind::DamagedRequest,
        UnansweredKind::InputEnded, UnansweredKind::AfterLoss}) {
    SessionTimeout t;
    t.kind = kind;
    tally.add(t);
  }
  EXPECT_EQ(tally.counts().timeouts, 2u);
  EXPECT_EQ(tally.counts().unanswered_damaged_requests, 1u);
  EXPECT_EQ(tally.counts().unanswered_at_end, 1u);
  EXPECT_EQ(tally.counts().unanswered_after_loss, 1u);
}

TEST(EventTally, GapsOfUnknownSizeAreCountedApart) {
  EventTally tally;
  tally.add(SessionGap{Direction::ToSlave, 1.0, 12});
  tally.add(SessionGap{Direction::ToSlave, 2.0, std::nullopt});
  EXPECT_EQ(tally.counts().gaps.gaps, 2u);
  EXPECT_EQ(tally.counts().gaps.lost_bytes, 12u);
  EXPECT_EQ(tally.counts().gaps.gaps_of_unknown_size, 1u);
}

TEST(EventTally, MergedTalliesAddUpAndKeepTheLatestLatency) {
  Frame frame;
  EventTally a;
  EventTally b;
  SessionFrame early = reply(frame, true, ReplyKind::Normal);
  early.latency = 0.030;
  early.end_time = 10.0;
  SessionFrame late = early;
  late.latency = 0.050;
  late.end_time = 20.0;
  b.add(late);
  a.add(early);
  a.add(early);
  EventTally run;
  run.merge(b);
  run.merge(a);
  EXPECT_EQ(run.counts().frames, 3u);
  EXPECT_EQ(run.latency().count(), 3u);
  EXPECT_DOUBLE_EQ(run.latency().summary().max, 0.050);
  EXPECT_DOUBLE_EQ(run.latency().summary().min, 0.030);
  ASSERT_TRUE(run.last_latency().has_value());
  EXPECT_DOUBLE_EQ(run.last_latency()->latency, 0.050);
  EXPECT_DOUBLE_EQ(run.last_latency()->at, 20.0);
}

}  // namespace
}  // namespace pvtap
