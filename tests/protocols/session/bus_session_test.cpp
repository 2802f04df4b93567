// BusSession: the core pipeline for one bus, as the analyzer and the live sniffer drive it.
#include "pvtap/session/bus_session.h"

#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

#include "frame_builders.h"
#include "hex_bytes.h"
#include "pvtap/codec/frame_codec.h"
#include "pvtap/session/event_tally.h"
#include "pvtap/statistics/bus_timing.h"

namespace pvtap {
namespace {

using Bytes = std::vector<std::uint8_t>;

Frame gsl_read(std::uint8_t station, std::uint16_t start, std::uint16_t count) {
  return test::read_request(Dialect::Gsl, station, 0x03, start, count);
}

Frame gsl_reply(std::uint8_t station, WordList words) {
  Frame f = test::frame_of(Dialect::Gsl, Role::Response, station, 0x03);
  f.byte_count = static_cast<std::uint8_t>(2 * words.size());
  f.words = words;
  return f;
}

Frame gsl_exception(std::uint8_t station, std::uint8_t code) {
  Frame f = test::frame_of(Dialect::Gsl, Role::Response, station, 0x83);
  f.exception_code = code;
  return f;
}

// Records what the session reports.
struct Recorder : BusSessionSink {
  void on_frame(const SessionFrame& f) override {
    frames.push_back(f);
    frames.back().bytes = {};
    frames.back().frame = nullptr;
    frames.back().values = {};
    value_texts.emplace_back();
    for (const DecodedValue& v : f.values) value_texts.back().push_back(std::string(v.key()));
    raw.emplace_back(f.bytes.begin(), f.bytes.end());
  }
  void on_timeout(const SessionTimeout& t) override { timeouts.push_back(t); }
  void on_noise(const SessionNoise& n) override { noise_bytes += n.noise.bytes.size(); }
  void on_gap(const SessionGap& g) override { gaps.push_back(g); }
  void on_line_error(const SessionLineError& e) override { line_errors.push_back(e); }
  void on_driver_glitch(const SessionDriverGlitch& g) override { glitches.push_back(g); }

  std::vector<SessionFrame> frames;
  std::vector<std::vector<std::string>> value_texts;
  std::vector<Bytes> raw;
  std::vector<SessionTimeout> timeouts;
  std::vector<SessionGap> gaps;
  std::vector<SessionLineError> line_errors;
  std::vector<SessionDriverGlitch> glitches;
  std::size_t noise_bytes = 0;
};

class BusSessionTest : public ::testing::Test {
 protected:
  void make(BusSessionOptions options = {}) {
    session_ = std::make_unique<BusSession>(options, decoder_, recorder_);
  }
  void feed(const Bytes& bytes, double time, Direction d = Direction::Unknown) {
    session_->feed(BusChunk{bytes, time, d});
  }
  const DecodedValue* latest(std::uint8_t station, std::string_view key) {
    report_ = session_->report();
    for (const StationSummary& s : report_.stations) {
      if (s.station != station) continue;
      for (const LatestValue& v : s.latest_values) {
        if (v.value.key() == key) return &v.value;
      }
    }
    return nullptr;
  }

  RegisterDecoder decoder_;
  Recorder recorder_;
  std::unique_ptr<BusSession> session_;
  BusReport report_;
};

TEST_F(BusSessionTest, TapOnTheBusGivesTransactionsLatencyAndLatestValues) {
  make();
  feed(encode_frame(gsl_read(1, 0x041A, 7)), 10.0);  // IDs 1050..1056
  feed(encode_frame(gsl_reply(1, {2301, 2302, 2303, 10, 11, 12, 5001})), 10.050);
  feed(encode_frame(gsl_read(1, 0x0420, 1)), 11.0);  // 1056 again
  feed(encode_frame(gsl_reply(1, {4999})), 11.030);
  session_->finish();

  ASSERT_EQ(recorder_.frames.size(), 4u);
  const SessionFrame& reply = recorder_.frames[1];
  EXPECT_EQ(reply.role, Role::Response);
  ASSERT_TRUE(reply.latency.has_value());
  // The reply's chunk time is its last byte: its start is 19 characters earlier.
  const double char_time = BusTiming(9600).char_time;
  EXPECT_NEAR(*reply.latency, 0.050 - 19 * char_time, 1e-9);
  EXPECT_EQ(recorder_.value_texts[1].size(), 7u);
  EXPECT_TRUE(recorder_.timeouts.empty());

  const DecodedValue* frequency = latest(1, "grid_frequency");
  ASSERT_NE(frequency, nullptr);
  EXPECT_NEAR(frequency->value, 49.99, 1e-9);  // the newer reply wins
  const DecodedValue* voltage = latest(1, "grid_voltage_ab");
  ASSERT_NE(voltage, nullptr);
  EXPECT_NEAR(voltage->value, 230.1, 1e-9);
  EXPECT_EQ(report_.requests, 2u);
  EXPECT_EQ(report_.responses, 2u);
  EXPECT_EQ(report_.transactions, 2u);
  ASSERT_EQ(report_.stations.size(), 1u);
  EXPECT_EQ(report_.stations[0].latency.count, 2u);
  EXPECT_EQ(report_.bytes.bytes_in, report_.bytes.frame_bytes + report_.bytes.noise_bytes);
}

// A gateway or pty faster than the configured baud rate: the reply's bytes arrive 2 ms after
// the request, although 19 characters take 20 ms at 9600 baud. Estimated back from its last
// byte, the reply would start before its request ended; on a half-duplex bus it cannot.
// Every register a reply carries is a latest value, mapped or not: words no map names keep
// their table (holding and input registers at one address apart), coils are bits.
// What the UART saw besides bytes goes through the session as every other event: handed on
// with its direction, and counted by the one tally, as a receiver counts: a character with
// both errors under each, a glitch's byte with the errors it was read with.
TEST_F(BusSessionTest, LineErrorsAndDriverGlitchesAreEventsOfTheBusAndItsCounts) {
  make();
  session_->line_error({1.0, 0.0005, 0x03, LineErrorKind::Framing, Direction::FromSlave});
  session_->line_error({1.1, 0.0005, 0x00, LineErrorKind::Parity, Direction::ToSlave});
  session_->line_error({1.2, 0.0005, 0x07, LineErrorKind::FramingAndParity, Direction::Unknown});
  session_->line_error({1.3, 0.002, 0, LineErrorKind::Break, Direction::Unknown});
  session_->driver_glitch({1.4, 0x00, true, true, false, Direction::FromSlave});
  session_->driver_glitch({1.5, 0xFE, false, false, true, Direction::FromSlave});
  session_->driver_glitch({1.6, 0xFF, false, false, false, Direction::ToSlave});
  session_->finish();

  ASSERT_EQ(recorder_.line_errors.size(), 4u);
  EXPECT_EQ(recorder_.line_errors[0].direction, Direction::FromSlave);
  EXPECT_EQ(recorder_.line_errors[3].kind, LineErrorKind::Break);
  ASSERT_EQ(recorder_.glitches.size(), 3u);
  EXPECT_EQ(recorder_.glitches[1].value, 0xFE);
  const LineErrorTally& counted = session_->tally().counts().line_errors;
  EXPECT_EQ(counted.framing_errors, 3u);  // framing, framing and parity, a glitch's
  EXPECT_EQ(counted.parity_errors, 3u);   // parity, framing and parity, a glitch's
  EXPECT_EQ(counted.breaks, 1u);
  EXPECT_EQ(counted.driver_glitches, 3u);
  const BusReport report = session_->report();
  EXPECT_EQ(report.line_errors.framing_errors, 3u);
  EXPECT_EQ(report.line_errors.driver_glitches, 3u);
}

TEST_F(BusSessionTest, UnmappedWordsAndBitsAreLatestValuesOfTheirTable) {
  make();
  const auto reply = [](std::uint8_t function, WordList words) {
    Frame f = test::frame_of(Dialect::Modbus, Role::Response, 7, function);
    f.byte_count = static_cast<std::uint8_t>(2 * words.size());
    f.words = words;
    return f;
  };
  feed(encode_frame(test::read_request(Dialect::Modbus, 7, 0x03, 0x2000, 2)), 1.0);
  feed(encode_frame(reply(0x03, {0x00E6, 0x0001})), 1.05);
  feed(encode_frame(test::read_request(Dialect::Modbus, 7, 0x04, 0x2000, 1)), 2.0);
  feed(encode_frame(reply(0x04, {0x1234})), 2.05);
  feed(encode_frame(test::read_request(Dialect::Modbus, 7, 0x01, 19, 10)), 3.0);
  Frame coils = test::frame_of(Dialect::Modbus, Role::Response, 7, 0x01);
  coils.byte_count = 2;
  coils.data = ByteList{0x05, 0x02};  // coils 19 and 21 on, 28 on
  feed(encode_frame(coils), 3.05);
  feed(encode_frame(test::read_request(Dialect::Modbus, 7, 0x03, 0x2000, 1)), 4.0);
  feed(encode_frame(reply(0x03, {0x00E7})), 4.05);  // newer: 0x2000 holding only
  session_->finish();

  report_ = session_->report();
  ASSERT_EQ(report_.stations.size(), 1u);
  std::map<std::string, std::uint32_t> seen;
  for (const LatestValue& v : report_.stations[0].latest_values) {
    EXPECT_FALSE(v.mapped());
    seen[std::string(unmapped_key(v.table, v.value.address).view())] = v.value.raw;
  }
  const std::map<std::string, std::uint32_t> expected{
      {"reg_0x2000", 0x00E7}, {"reg_0x2001", 1},  {"input_reg_0x2000", 0x1234}, {"coil_0x0013", 1},
      {"coil_0x0014", 0},     {"coil_0x0015", 1}, {"coil_0x0016", 0},           {"coil_0x0017", 0},
      {"coil_0x0018", 0},     {"coil_0x0019", 0}, {"coil_0x001a", 0},           {"coil_0x001b", 0},
      {"coil_0x001c", 1}};
  EXPECT_EQ(seen, expected);
}

TEST_F(BusSessionTest, FrameNeverStartsBeforeThePreviousFrameEnded) {
  BusSessionOptions options;
  options.reassembler.timestamps = TimestampTrust::Untrusted;
  make(options);
  feed(encode_frame(gsl_read(1, 0x041A, 7)), 20.0, Direction::ToSlave);
  feed(encode_frame(gsl_reply(1, {1, 2, 3, 4, 5, 6, 7})), 20.002, Direction::FromSlave);
  session_->finish();

  ASSERT_EQ(recorder_.frames.size(), 2u);
  const SessionFrame& reply = recorder_.frames[1];
  EXPECT_DOUBLE_EQ(reply.start_time, recorder_.frames[0].end_time);
  EXPECT_DOUBLE_EQ(reply.end_time, 20.002);
  ASSERT_TRUE(reply.latency.has_value());
  EXPECT_DOUBLE_EQ(*reply.latency, 0.0);
}

TEST_F(BusSessionTest, TimeoutsExceptionsAndTheEndOfInputAreJudgedApart) {
  make();
  feed(encode_frame(gsl_read(2, 0x041A, 1)), 1.0);  // never answered: a timeout
  feed(encode_frame(gsl_read(3, 0x041A, 1)), 3.0);
  feed(encode_frame(gsl_exception(3, 0x02)), 3.02);
  feed(test::hex_bytes("06 18 10 2A 09 3C 03 36"), 4.0);
  // Hybrid error reply with a good CRC (the reference's vector has a bad one).
  Frame error = test::frame_of(Dialect::Hybrid, Role::Response, 6, 0xFF);
  error.byte_count = 8;
  error.device = DeviceNumber{0x31, 103};
  error.start = 0x1000;
  error.count = 0x00FF;
  feed(encode_frame(error), 4.05);
  feed(encode_frame(gsl_read(4, 0x041A, 1)), 9.0);  // the input ends 0.5 s later
  feed(Bytes{0x00}, 9.5);                           // one noise byte
  session_->finish();
  report_ = session_->report();

  ASSERT_EQ(recorder_.timeouts.size(), 2u);
  EXPECT_EQ(recorder_.timeouts[0].kind, UnansweredKind::Timeout);
  EXPECT_EQ(recorder_.timeouts[0].timeout.station, 2);
  EXPECT_EQ(recorder_.timeouts[1].kind, UnansweredKind::InputEnded);
  EXPECT_EQ(report_.timeouts, 1u);
  EXPECT_EQ(report_.unanswered_at_end, 1u);
  EXPECT_EQ(report_.exceptions, 2u);
  ASSERT_EQ(report_.exception_codes.size(), 2u);
  EXPECT_EQ(report_.exception_codes[0].dialect, Dialect::Hybrid);
  EXPECT_EQ(report_.exception_codes[0].code, 0xFF);
  EXPECT_EQ(report_.exception_codes[1].dialect, Dialect::Gsl);
  EXPECT_EQ(report_.exception_codes[1].code, 0x02);
  EXPECT_EQ(report_.bytes.noise_bytes, 1u);
  EXPECT_EQ(recorder_.noise_bytes, 1u);
}

// A logger reading four blocks of one inverter every 5 s: one poll period per block, taken
// from the requests' start and count, with a damaged request left out of every block.
TEST_F(BusSessionTest, PollPeriodsArePerBlockOfRegisters) {
  make();
  const std::uint16_t blocks[][2] = {{0x03E8, 10}, {0x0406, 4}, {0x041A, 7}, {0x044C, 2}};
  for (int round = 0; round < 6; ++round) {
    for (int b = 0; b < 4; ++b) {
      const double t = 50.0 + 5.0 * round + 0.25 * b;
      Bytes request = encode_frame(gsl_read(2, blocks[b][0], blocks[b][1]));
      if (round == 3 && b == 1) request[2] ^= 0x40;  // start address hit: bad CRC, no reply
      feed(request, t);
      if (round == 3 && b == 1) continue;
      WordList words;
      for (std::uint16_t w = 0; w < blocks[b][1]; ++w) words.push_back(w);
      feed(encode_frame(gsl_reply(2, words)), t + 0.06);
    }
  }
  session_->finish();
  report_ = session_->report();

  EXPECT_EQ(report_.bytes.bad_frames, 1u);
  const std::vector<PollPeriod>& polls = report_.timing.poll_periods;
  ASSERT_EQ(polls.size(), 4u);
  for (std::size_t b = 0; b < 4; ++b) {
    EXPECT_EQ(polls[b].block.station, 2);
    EXPECT_EQ(polls[b].block.function, 0x03);
    EXPECT_EQ(polls[b].block.start, blocks[b][0]);
    EXPECT_EQ(polls[b].block.count, blocks[b][1]);
    if (b == 1) {
      EXPECT_EQ(polls[b].period.intervals, 4u);  // five good requests
      EXPECT_NEAR(polls[b].period.mean, 6.25, 1e-6);
      EXPECT_NEAR(polls[b].period.max, 10.0, 1e-6);
      continue;
    }
    EXPECT_EQ(polls[b].period.intervals, 5u);
    EXPECT_NEAR(polls[b].period.mean, 5.0, 1e-6);
    EXPECT_LT(polls[b].period.stddev, 1e-6);
    EXPECT_LT(polls[b].period.max_deviation, 1e-6);
  }
  EXPECT_EQ(report_.timing.untracked_poll_requests, 0u);
}

TEST_F(BusSessionTest, BadCheckRequestOfOneDirectionEndsWithTheTurn) {
  make();
  Bytes bad_request = encode_frame(gsl_read(1, 0x041A, 1));
  bad_request[7] ^= 0x55;
  feed(bad_request, 1.0, Direction::ToSlave);
  // The reply arrives in two pieces; the master's turn ended when the slave began.
  session_->end_turn(Direction::ToSlave);
  const Bytes reply = encode_frame(gsl_reply(1, {2300}));
  feed(Bytes(reply.begin(), reply.begin() + 3), 1.05, Direction::FromSlave);
  feed(Bytes(reply.begin() + 3, reply.end()), 1.06, Direction::FromSlave);
  session_->finish();
  report_ = session_->report();

  ASSERT_EQ(recorder_.frames.size(), 2u);
  EXPECT_FALSE(recorder_.frames[0].check.ok);
  EXPECT_EQ(recorder_.frames[0].role, Role::Request);
  EXPECT_TRUE(recorder_.frames[1].request_id.has_value());  // answered, not unsolicited
  EXPECT_FALSE(recorder_.frames[1].unsolicited);
  EXPECT_EQ(report_.bytes.bad_frames, 1u);
  ASSERT_EQ(report_.bad_check_examples.size(), 1u);
  EXPECT_EQ(report_.bad_check_examples[0].bytes, bad_request);
  // The bad request's start address is not trusted to place the reply's words.
  EXPECT_EQ(latest(1, "grid_voltage_ab"), nullptr);
}

TEST_F(BusSessionTest, LossInOneDirectionLeavesTheOtherIntact) {
  make();
  feed(encode_frame(gsl_read(1, 0x041A, 1)), 1.0, Direction::ToSlave);
  const Bytes reply = encode_frame(gsl_reply(1, {2300}));
  feed(Bytes(reply.begin(), reply.begin() + 4), 1.05, Direction::FromSlave);
  session_->data_lost(Direction::ToSlave, 1.055, 12);
  feed(Bytes(reply.begin() + 4, reply.end()), 1.06, Direction::FromSlave);
  const Bytes cut = encode_frame(gsl_read(2, 0x041A, 1));
  feed(Bytes(cut.begin(), cut.begin() + 5), 2.0, Direction::ToSlave);
  session_->data_lost(Direction::ToSlave, 2.5, std::nullopt);
  session_->finish();
  report_ = session_->report();

  ASSERT_EQ(recorder_.frames.size(), 2u);
  EXPECT_TRUE(recorder_.frames[1].request_id.has_value());
  ASSERT_EQ(recorder_.gaps.size(), 2u);
  EXPECT_EQ(recorder_.gaps[0].lost_bytes, 12u);
  EXPECT_FALSE(recorder_.gaps[1].lost_bytes.has_value());
  EXPECT_EQ(report_.gaps.gaps, 2u);
  EXPECT_EQ(report_.gaps.lost_bytes, 12u);
  EXPECT_EQ(report_.gaps.gaps_of_unknown_size, 1u);
  EXPECT_EQ(recorder_.noise_bytes, 5u);  // what was left of the cut request
  EXPECT_EQ(report_.bytes.bytes_in, report_.bytes.frame_bytes + report_.bytes.noise_bytes);
}

TEST_F(BusSessionTest, RequestWaitingDuringALossIsNotATimeout) {
  make();
  feed(encode_frame(gsl_read(1, 0x041A, 1)), 1.0, Direction::ToSlave);
  session_->data_lost(Direction::FromSlave, 1.1, 40);
  feed(encode_frame(gsl_read(1, 0x041A, 1)), 5.0, Direction::ToSlave);
  feed(encode_frame(gsl_reply(1, {2300})), 5.05, Direction::FromSlave);
  session_->finish();
  report_ = session_->report();
  ASSERT_EQ(recorder_.timeouts.size(), 1u);
  EXPECT_EQ(recorder_.timeouts[0].kind, UnansweredKind::AfterLoss);
  EXPECT_EQ(report_.timeouts, 0u);
  EXPECT_EQ(report_.unanswered_after_loss, 1u);
}

TEST_F(BusSessionTest, PlainDumpHasNoLatencyAndSaysWhyTimingIsNotJudged) {
  BusSessionOptions options;
  options.has_timestamps = false;
  options.reassembler.timestamps = TimestampTrust::Untrusted;
  make(options);
  Bytes all = encode_frame(gsl_read(1, 0x041A, 1));
  const Bytes reply = encode_frame(gsl_reply(1, {2300}));
  all.insert(all.end(), reply.begin(), reply.end());
  feed(all, 0.0);
  session_->finish();
  report_ = session_->report();
  ASSERT_EQ(recorder_.frames.size(), 2u);
  EXPECT_FALSE(recorder_.frames[1].latency.has_value());
  EXPECT_TRUE(recorder_.frames[1].request_id.has_value());
  EXPECT_FALSE(report_.timing.bus.measurable);
  EXPECT_NE(report_.timing.bus.not_measurable_reason.find("no timestamps"), std::string::npos);
  EXPECT_EQ(report_.timing.latency.count, 0u);
}

TEST_F(BusSessionTest, WithoutValueDecodingTheLatestTableIsStillKept) {
  BusSessionOptions options;
  options.decode_values = false;
  make(options);
  feed(encode_frame(test::ascii_reply(1, 0x0020, {266, 57})), 1.0);  // carries its start
  session_->finish();
  ASSERT_EQ(recorder_.frames.size(), 1u);
  EXPECT_TRUE(recorder_.value_texts[0].empty());
  EXPECT_TRUE(recorder_.frames[0].unsolicited);
  const DecodedValue* pv = latest(1, "pv_voltage");
  ASSERT_NE(pv, nullptr);
  EXPECT_DOUBLE_EQ(pv->value, 266.0);
}

TEST_F(BusSessionTest, HybridRepliesCarryTheDeviceNumberFirst) {
  make();
  feed(test::hex_bytes("FF 11 10 60 00 02 6D 08"), 1.0);
  feed(test::hex_bytes("09 11 08 22 00 00 6B 22 00 00 6B F2 77"), 1.05);
  session_->finish();
  ASSERT_EQ(recorder_.frames.size(), 2u);
  EXPECT_TRUE(recorder_.frames[1].broadcast_answer);
  ASSERT_FALSE(recorder_.value_texts[1].empty());
  EXPECT_EQ(recorder_.value_texts[1][0], "device_number");
  const DecodedValue* device = latest(9, "device_number");
  ASSERT_NE(device, nullptr);
  EXPECT_EQ(device->device.serial, 107u);
}

}  // namespace
}  // namespace pvtap
