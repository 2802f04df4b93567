// Station rule: a station exists because a frame with a good check names it; a damaged frame
// belongs to the station of the good frame it is paired with, or to the unknown station.
#include "pvtap/session/station_rule.h"

#include <gtest/gtest.h>

#include <vector>

#include "frame_builders.h"
#include "pvtap/codec/frame_codec.h"
#include "pvtap/session/bus_session.h"

namespace pvtap {
namespace {

using Bytes = std::vector<std::uint8_t>;

Bytes gsl_read(std::uint8_t station) {
  return encode_frame(test::read_request(Dialect::Gsl, station, 0x03, 0x041A, 1));
}

Bytes gsl_reply(std::uint8_t station) {
  Frame f = test::frame_of(Dialect::Gsl, Role::Response, station, 0x03);
  f.byte_count = 2;
  f.words = {2300};
  return encode_frame(f);
}

// The frame with its station byte changed: its CRC no longer holds.
Bytes claiming(Bytes frame, std::uint8_t station) {
  frame[0] = station;
  return frame;
}

struct Recorder : BusSessionSink {
  void on_frame(const SessionFrame& f) override { stations.push_back(f.station); }
  void on_timeout(const SessionTimeout& t) override { timeouts.push_back(t); }
  std::vector<std::optional<std::uint8_t>> stations;
  std::vector<SessionTimeout> timeouts;
};

class StationRuleTest : public ::testing::Test {
 protected:
  void feed(const Bytes& bytes, double time) { session_.feed(BusChunk{bytes, time}); }
  BusReport finish() {
    session_.finish();
    return session_.report();
  }
  static std::vector<std::uint8_t> addresses(const BusReport& r) {
    std::vector<std::uint8_t> out;
    for (const StationSummary& s : r.stations) out.push_back(s.station);
    return out;
  }

  RegisterDecoder decoder_;
  Recorder recorder_;
  BusSession session_{BusSessionOptions{}, decoder_, recorder_};
};

TEST_F(StationRuleTest, DamagedReplyBelongsToItsRequestsStation) {
  feed(gsl_read(1), 1.0);
  feed(claiming(gsl_reply(1), 88), 1.05);
  const BusReport r = finish();

  ASSERT_EQ(recorder_.stations.size(), 2u);
  EXPECT_EQ(recorder_.stations[1], std::optional<std::uint8_t>(1));
  EXPECT_EQ(addresses(r), std::vector<std::uint8_t>{1});
  EXPECT_EQ(r.stations[0].responses, 1u);
  EXPECT_EQ(r.stations[0].bad_checks, 1u);
  EXPECT_EQ(r.stations[0].damaged_replies, 1u);
  EXPECT_EQ(r.unknown_station.damaged_frames, 0u);
}

TEST_F(StationRuleTest, UnansweredDamagedRequestIsOfTheUnknownStation) {
  feed(gsl_read(2), 1.0);
  feed(gsl_reply(2), 1.05);
  feed(claiming(gsl_read(2), 88), 2.0);
  feed(gsl_read(2), 4.0);  // the master's next poll, long after the timeout
  feed(gsl_reply(2), 4.05);
  const BusReport r = finish();

  EXPECT_EQ(addresses(r), std::vector<std::uint8_t>{2});
  EXPECT_EQ(r.stations[0].requests, 2u);
  EXPECT_EQ(r.stations[0].bad_checks, 0u);
  ASSERT_EQ(recorder_.timeouts.size(), 1u);
  EXPECT_EQ(recorder_.timeouts[0].kind, UnansweredKind::DamagedRequest);
  EXPECT_FALSE(recorder_.timeouts[0].station.has_value());
  EXPECT_EQ(r.unknown_station.damaged_frames, 1u);
  EXPECT_EQ(r.unknown_station.unanswered_damaged_requests, 1u);
  ASSERT_EQ(r.unknown_station.claimed.size(), 1u);
  EXPECT_EQ(r.unknown_station.claimed[0].station, 88);
  EXPECT_EQ(r.unknown_station.claimed[0].frames, 1u);
}

TEST_F(StationRuleTest, UnpairedDamagedReplyKeepsTheAddressItClaimed) {
  feed(gsl_read(1), 1.0);
  feed(gsl_reply(1), 1.05);
  feed(claiming(gsl_reply(1), 33), 3.0);  // no request waits: unsolicited
  const BusReport r = finish();

  ASSERT_EQ(recorder_.stations.size(), 3u);
  EXPECT_FALSE(recorder_.stations[2].has_value());
  EXPECT_EQ(addresses(r), std::vector<std::uint8_t>{1});
  EXPECT_EQ(r.stations[0].unsolicited, 0u);
  EXPECT_EQ(r.unknown_station.damaged_frames, 1u);
  ASSERT_EQ(r.unknown_station.claimed.size(), 1u);
  EXPECT_EQ(r.unknown_station.claimed[0].station, 33);
}

TEST_F(StationRuleTest, DamagedRequestAnsweredByAGoodReplyIsTheRepliersRequest) {
  Bytes request = gsl_read(3);
  request[7] ^= 0x55;  // the CRC, not the station, is damaged
  feed(request, 1.0);
  feed(gsl_reply(3), 1.05);
  const BusReport r = finish();

  EXPECT_FALSE(recorder_.stations[0].has_value());  // settled by its reply, not on arrival
  EXPECT_EQ(addresses(r), std::vector<std::uint8_t>{3});
  EXPECT_EQ(r.stations[0].requests, 1u);
  EXPECT_EQ(r.stations[0].bad_checks, 1u);
  EXPECT_EQ(r.unknown_station.damaged_frames, 0u);
}

TEST_F(StationRuleTest, LatencyOfTwoDamagedFramesIsOfNoStation) {
  Bytes request = gsl_read(4);
  request[7] ^= 0x55;
  feed(request, 1.0);
  feed(claiming(gsl_reply(4), 44), 1.05);  // answers the one pending request
  const BusReport r = finish();

  EXPECT_TRUE(r.stations.empty());
  EXPECT_TRUE(r.timing.latency_by_station.empty());
  EXPECT_EQ(r.timing.latency.count, 1u);
  EXPECT_EQ(r.unknown_station.damaged_frames, 2u);
  ASSERT_EQ(r.unknown_station.claimed.size(), 2u);
  EXPECT_EQ(r.unknown_station.claimed[0].station, 4);
  EXPECT_EQ(r.unknown_station.claimed[1].station, 44);
}

TEST(StationRule, TransactionIsNamedByAFrameWithAGoodCheck) {
  Transaction t;
  t.station = 5;
  EXPECT_EQ(transaction_station(t), std::optional<std::uint8_t>(5));
  t.reply_check_ok = false;
  EXPECT_EQ(transaction_station(t), std::optional<std::uint8_t>(5));
  t.request_check_ok = false;
  EXPECT_FALSE(transaction_station(t).has_value());
  t.reply_check_ok = true;
  t.request_check_ok = true;
  t.broadcast = true;  // the request names every station: only the reply names one
  EXPECT_EQ(transaction_station(t), std::optional<std::uint8_t>(5));
  t.reply_check_ok = false;
  EXPECT_FALSE(transaction_station(t).has_value());
}

TEST(StationRule, MergedUnknownStationsAddUpByAddress) {
  UnknownStation a;
  a.damaged_frames = 2;
  a.claimed = {{33, 1}, {88, 1}};
  UnknownStation b;
  b.damaged_frames = 2;
  b.unanswered_damaged_requests = 1;
  b.claimed = {{13, 1}, {88, 1}};
  a += b;
  EXPECT_EQ(a.damaged_frames, 4u);
  EXPECT_EQ(a.unanswered_damaged_requests, 1u);
  ASSERT_EQ(a.claimed.size(), 3u);
  EXPECT_EQ(a.claimed[0].station, 13);
  EXPECT_EQ(a.claimed[1].station, 33);
  EXPECT_EQ(a.claimed[2].station, 88);
  EXPECT_EQ(a.claimed[2].frames, 2u);
}

}  // namespace
}  // namespace pvtap
