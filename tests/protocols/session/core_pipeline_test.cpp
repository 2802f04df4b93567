// The core's parts chained as both programs use them: reassembler -> parser -> matcher ->
// register decoder, on one bus carrying all three dialects.
#include <gtest/gtest.h>

#include "frame_builders.h"

#include <map>

#include "hex_bytes.h"
#include "pvtap/codec/frame_codec.h"
#include "pvtap/framing/stream_reassembler.h"
#include "pvtap/matching/transaction_matcher.h"
#include "pvtap/registers/register_decoder.h"
#include "pvtap/registers/register_map.h"
#include "pvtap/statistics/bus_timing.h"

namespace pvtap {
namespace {

Frame gsl_frame(Role role, std::uint8_t station, std::uint16_t start, WordList words) {
  Frame f = test::frame_of(Dialect::Gsl, role, station, 0x03);
  if (role == Role::Request) {
    f.start = start;
    f.count = static_cast<std::uint16_t>(words.size());
  } else {
    f.byte_count = static_cast<std::uint8_t>(2 * words.size());
    f.words = words;
  }
  return f;
}

// Collects what the pipeline reports: frames by id, transactions, timeouts, decoded values.
class Pipeline : public ReassemblerSink {
 public:
  void on_frame(const FrameEvent& e) override {
    const auto parsed = parse_frame(e.bytes, e.dialect, e.role);
    ASSERT_TRUE(parsed) << parsed.diagnostics();
    const std::uint64_t id = next_id_++;
    frames_[id] = parsed.value();
    const FrameMatch match = matcher_.on_frame(
        ObservedFrame{id, summarize(parsed.value()), e.start_time, e.end_time, e.check.ok, false});
    add_timeouts(match.timeouts);
    if (match.transaction) {
      transactions.push_back(*match.transaction);
      decoder_.decode(frames_[match.transaction->response_id],
                      &frames_[match.transaction->request_id], values);
    }
  }
  void on_noise(const NoiseEvent& e) override { noise_bytes += e.bytes.size(); }
  void finish() { add_timeouts(matcher_.finish()); }

  const DecodedValue* value(std::string_view key) const {
    for (const auto& v : values) {
      if (v.def && v.key() == key) return &v;
    }
    return nullptr;
  }

  std::vector<Transaction> transactions;
  std::vector<Timeout> timeouts;
  std::vector<DecodedValue> values;
  std::size_t noise_bytes = 0;

 private:
  void add_timeouts(std::span<const Timeout> decided) {
    timeouts.insert(timeouts.end(), decided.begin(), decided.end());
  }

  TransactionMatcher matcher_;
  RegisterDecoder decoder_;
  std::map<std::uint64_t, Frame> frames_;
  std::uint64_t next_id_ = 0;
};

TEST(CorePipeline, MixedBusGivesTransactionsTimeoutsAndValues) {
  std::vector<std::vector<std::uint8_t>> frames = {
      test::hex_bytes("05 30 31 52 30 30 32 30 30 32 30 31 64 37 04"),  // ASCII PV read
      encode_frame(test::ascii_reply(1, 0x0020, {266, 57})),
      test::hex_bytes("FF 11 10 60 00 02 6D 08"),  // Hybrid broadcast device info
      test::hex_bytes("09 11 08 22 00 00 6B 22 00 00 6B F2 77"),
      encode_frame(gsl_frame(Role::Request, 1, 0x0420, {0})),  // GSL ID 1056 (grid frequency)
      encode_frame(gsl_frame(Role::Response, 1, 0, {6001})),
      encode_frame(gsl_frame(Role::Request, 2, 0x0420, {0})),  // never answered
  };

  Pipeline p;
  StreamReassembler r({}, p);
  const BusTiming timing(9600);
  double t = 100.0;
  for (const auto& f : frames) {
    // Three bytes per read, as a slow USB adapter might deliver them, then the reply gap.
    for (std::size_t at = 0; at < f.size(); at += 3) {
      const auto piece = std::span(f).subspan(at, std::min<std::size_t>(3, f.size() - at));
      t += static_cast<double>(piece.size()) * timing.char_time;
      r.feed(BusChunk{piece, t, Direction::Unknown});
    }
    t += 0.020;
  }
  r.finish();
  p.finish();

  EXPECT_EQ(p.noise_bytes, 0u);
  ASSERT_EQ(p.transactions.size(), 3u);
  EXPECT_NEAR(p.transactions[0].latency, 0.020, 1e-6);
  EXPECT_EQ(p.transactions[1].station, 9);  // the broadcast answered from the real address
  ASSERT_EQ(p.timeouts.size(), 1u);
  EXPECT_EQ(p.timeouts[0].station, 2);

  const DecodedValue* pv_voltage = p.value("pv_voltage");
  ASSERT_NE(pv_voltage, nullptr);
  EXPECT_DOUBLE_EQ(pv_voltage->value, 266.0);
  const DecodedValue* pv_current = p.value("pv_current");
  ASSERT_NE(pv_current, nullptr);
  EXPECT_NEAR(pv_current->value, 5.7, 1e-9);
  const DecodedValue* frequency = p.value("grid_frequency");
  ASSERT_NE(frequency, nullptr);
  EXPECT_NEAR(frequency->value, 60.01, 1e-9);
  EXPECT_EQ(frequency->unit(), "Hz");
}

}  // namespace
}  // namespace pvtap
