// apply_timestamping: what each way of reaching pvtap lets the timestamps prove.
#include "pvtap/session/timestamping.h"

#include <gtest/gtest.h>

#include "pvtap/statistics/bus_timing.h"

namespace pvtap {
namespace {

BusSessionOptions applied(const TimestampFacts& facts) {
  BusSessionOptions o;
  apply_timestamping(facts, o);
  return o;
}

void expect_untouched(const BusSessionOptions& o) {
  const BusSessionOptions defaults;
  EXPECT_EQ(o.reassembler.timestamps, defaults.reassembler.timestamps);
  EXPECT_EQ(o.reassembler.boundary_gap, defaults.reassembler.boundary_gap);
  EXPECT_EQ(o.reassembler.segment_ends_pin, defaults.reassembler.segment_ends_pin);
  EXPECT_EQ(o.has_timestamps, defaults.has_timestamps);
  EXPECT_TRUE(o.timestamp_note.empty());
}

TEST(TimestampFacts, PerCharacterStampsAndExportedPdusAreJudgedByTheReassembler) {
  expect_untouched(applied({Timestamping::SerialCharacters, 0.5, 16}));
  expect_untouched(applied({Timestamping::ExportedPdus, 0.5, 16}));
}

TEST(TimestampFacts, BatchedSerialRecordsAreUntrustedWithoutABoundaryGap) {
  const BusSessionOptions o = applied({Timestamping::SerialBatches, 0.5, {}});
  EXPECT_EQ(o.reassembler.timestamps, TimestampTrust::Untrusted);
  EXPECT_EQ(o.reassembler.boundary_gap, ReassemblerOptions{}.boundary_gap);
  EXPECT_FALSE(o.reassembler.segment_ends_pin);
  EXPECT_TRUE(o.has_timestamps);
  EXPECT_EQ(o.timestamp_note,
            "the capture's records are chunks read from a serial adapter: their timestamps are "
            "batched (e.g. by a USB adapter's latency timer), not per character");
}

TEST(TimestampFacts, LoggerStickFramesAreTimedAtTheLanSide) {
  const BusSessionOptions o = applied({Timestamping::LoggerStickFrames, 0.025, {}});
  EXPECT_EQ(o.reassembler.timestamps, TimestampTrust::Untrusted);
  EXPECT_EQ(o.reassembler.boundary_gap, 0.0);
  EXPECT_TRUE(o.has_timestamps);
  EXPECT_EQ(o.timestamp_note,
            "latency is measured at the LAN side: the timestamps are those of the logger "
            "stick's Solarman V5 frames on TCP, not of bus characters");
}

TEST(TimestampFacts, GatewaySegmentsProveBoundariesByTheirGapAndPinSegmentEnds) {
  const BusSessionOptions o = applied({Timestamping::GatewaySegments, 0.025, {}});
  EXPECT_EQ(o.reassembler.timestamps, TimestampTrust::Untrusted);
  EXPECT_EQ(o.reassembler.boundary_gap, 0.025);
  EXPECT_TRUE(o.reassembler.segment_ends_pin);
  EXPECT_TRUE(o.has_timestamps);
  EXPECT_EQ(o.timestamp_note,
            "the timestamps are those of the gateway's TCP/UDP segments, not of bus characters");
}

TEST(TimestampFacts, APlainDumpHasNoTime) {
  const BusSessionOptions o = applied({Timestamping::PlainDump, 0.5, 16});
  EXPECT_FALSE(o.has_timestamps);
  EXPECT_EQ(o.reassembler.timestamps, TimestampTrust::Untrusted);
  EXPECT_FALSE(o.reassembler.segment_ends_pin);
  EXPECT_TRUE(o.timestamp_note.empty());
}

TEST(TimestampFacts, ALiveTapIsBatchedOnlyByALatencyTimerLongerThanT15) {
  expect_untouched(applied({Timestamping::LiveSerial, 0.0, {}}));  // a pty or a non-FTDI adapter
  expect_untouched(applied({Timestamping::LiveSerial, 0.0, 1}));   // 1 ms < t1.5 at 9600 baud

  const BusSessionOptions o = applied({Timestamping::LiveSerial, 0.0, 16});
  const BusTiming timing(9600);
  EXPECT_EQ(o.reassembler.timestamps, TimestampTrust::Untrusted);
  EXPECT_DOUBLE_EQ(o.reassembler.boundary_gap, 0.016 + timing.t35);
  EXPECT_FALSE(o.reassembler.segment_ends_pin);
  EXPECT_EQ(o.timestamp_note,
            "the adapter's USB latency timer is 16 ms: reads come in batches too coarse to judge "
            "t1.5/t3.5");
}

TEST(TimestampFacts, TheLatencyTimerIsJudgedAtTheSessionsOwnLineSpeed) {
  BusSessionOptions o;
  o.reassembler.baud = 1200;  // t1.5 = 12.5 ms: a 4 ms timer is fine enough
  apply_timestamping({Timestamping::LiveSerial, 0.0, 4}, o);
  EXPECT_EQ(o.reassembler.timestamps, TimestampTrust::Auto);
  o.reassembler.baud = 19200;  // t1.5 = 0.78 ms
  apply_timestamping({Timestamping::LiveSerial, 0.0, 4}, o);
  EXPECT_EQ(o.reassembler.timestamps, TimestampTrust::Untrusted);
}

TEST(TimestampFacts, LogicSamplesAreTrustedAndNameTheirClock) {
  BusSessionOptions o;
  apply_sample_clock(4e6, o);
  EXPECT_EQ(o.reassembler.timestamps, TimestampTrust::Trusted);
  EXPECT_TRUE(o.has_timestamps);
  EXPECT_TRUE(o.timestamp_note.empty());
  EXPECT_EQ(o.timestamp_source, "logic analyzer at 4 MS/s");
  apply_sample_clock(24e6, o);
  EXPECT_EQ(o.timestamp_source, "logic analyzer at 24 MS/s");
}

}  // namespace
}  // namespace pvtap
