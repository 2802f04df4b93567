// Plain Modbus devices on a bus of inverters: framing, pairing, labelling and naming, as the
// session reports them.
#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

#include "hex_bytes.h"
#include "pvtap/codec/checksums.h"
#include "pvtap/registers/coil_bits.h"
#include "pvtap/session/bus_session.h"

namespace pvtap {
namespace {

using Bytes = std::vector<std::uint8_t>;

// An ADU from a station and the PDU in hex, with its CRC.
Bytes adu(std::uint8_t station, std::string_view pdu) {
  Bytes out{station};
  const Bytes body = test::hex_bytes(pdu);
  out.insert(out.end(), body.begin(), body.end());
  const std::uint16_t crc = Crc16Modbus::compute(out);
  out.push_back(static_cast<std::uint8_t>(crc & 0xFF));
  out.push_back(static_cast<std::uint8_t>(crc >> 8));
  return out;
}

struct Seen {
  Dialect dialect;
  Role role;
  std::uint8_t function;
  bool check_ok;
  bool malformed;
  std::optional<std::uint64_t> request_id;
  std::optional<ByteCountMismatch> mismatch;
  std::optional<QuantityProblem> quantity;
  std::optional<WriteCountProblem> write_count;
  std::optional<Dialect> changed_from;
  std::optional<std::uint16_t> first_coil;
  unsigned coils_on = 0;
};

struct Recorder : BusSessionSink {
  void on_frame(const SessionFrame& f) override {
    Seen s{};
    s.dialect = f.dialect;
    s.role = f.role;
    s.function = f.frame ? f.frame->function : std::uint8_t{0};
    s.check_ok = f.check.ok;
    s.malformed = !f.parse_error.empty();
    s.request_id = f.request_id;
    s.mismatch = f.count_mismatch;
    s.quantity = f.quantity_problem;
    s.write_count = f.write_count_problem;
    s.changed_from = f.dialect_changed_from;
    if (f.frame != nullptr) {
      if (f.role == Role::Request) requests[f.frame->station] = *f.frame;
      const Frame* request = f.role == Role::Response && requests.contains(f.frame->station)
                                 ? &requests[f.frame->station]
                                 : nullptr;
      if (const auto bits = coil_bits(*f.frame, request)) {
        s.first_coil = bits->start;
        for (std::size_t i = 0; i < bits->count; ++i) s.coils_on += bits->on(i) ? 1u : 0u;
      }
    }
    frames.push_back(s);
  }
  void on_timeout(const SessionTimeout& t) override { timeouts.push_back(t); }
  void on_noise(const SessionNoise& n) override { noise_bytes += n.noise.bytes.size(); }

  std::map<std::uint8_t, Frame> requests;
  std::vector<Seen> frames;
  std::vector<SessionTimeout> timeouts;
  std::size_t noise_bytes = 0;
};

class ModbusBus : public ::testing::Test {
 protected:
  void SetUp() override { make({}); }
  void make(BusSessionOptions options) {
    options.reassembler.timestamps = TimestampTrust::Untrusted;
    session_ = std::make_unique<BusSession>(options, decoder_, recorder_);
  }
  // One frame per chunk, 50 ms apart, as a tap with one record per frame gives them.
  void send(const Bytes& bytes) {
    session_->feed(BusChunk{bytes, time_, Direction::Unknown});
    time_ += 0.05;
  }
  void exchange(std::uint8_t station, std::string_view request, std::string_view reply) {
    send(adu(station, request));
    send(adu(station, reply));
  }
  BusReport finish() {
    session_->finish();
    return session_->report();
  }

  RegisterDecoder decoder_;
  Recorder recorder_;
  std::unique_ptr<BusSession> session_;
  double time_ = 1000.0;
};

// The kinds of the IO module recording: 0x01 0x02 0x03 0x04 0x05 0x06 0x0F 0x10.
TEST_F(ModbusBus, EveryFrameOfAnIoModuleIsAFramePairedWithItsRequest) {
  exchange(0x11, "01 00 13 00 13", "01 03 CD 6B 05");
  exchange(0x11, "02 00 C4 00 16", "02 03 AC DB 35");
  exchange(0x11, "03 00 6B 00 03", "03 06 02 2B 00 00 00 64");
  exchange(0x11, "04 00 08 00 01", "04 02 00 0A");
  exchange(0x11, "05 00 AC FF 00", "05 00 AC FF 00");
  exchange(0x11, "06 00 01 00 03", "06 00 01 00 03");
  exchange(0x11, "0F 00 13 00 0A 02 CD 01", "0F 00 13 00 0A");
  exchange(0x11, "10 00 01 00 02 04 00 0A 01 02", "10 00 01 00 02");
  const BusReport report = finish();
  ASSERT_EQ(recorder_.frames.size(), 16u);
  EXPECT_EQ(recorder_.noise_bytes, 0u);
  EXPECT_TRUE(recorder_.timeouts.empty());
  for (std::size_t i = 0; i < recorder_.frames.size(); ++i) {
    const Seen& s = recorder_.frames[i];
    EXPECT_EQ(s.dialect, Dialect::Modbus) << i;
    EXPECT_EQ(s.role, i % 2 == 0 ? Role::Request : Role::Response) << i;
    if (i % 2 == 1) {
      EXPECT_TRUE(s.request_id) << i;
    }
    EXPECT_FALSE(s.changed_from) << i;
  }
  // Read coils 0x13.., 19 of them: CD and 6B have 5 set each, the 3 coils of 05 two.
  EXPECT_EQ(recorder_.frames[1].first_coil, 0x13);
  EXPECT_EQ(recorder_.frames[1].coils_on, 12u);
  EXPECT_EQ(report.transactions, 8u);
  ASSERT_EQ(report.stations.size(), 1u);
  EXPECT_EQ(report.stations[0].by_dialect[static_cast<std::size_t>(Dialect::Modbus)].requests, 8u);
}

TEST_F(ModbusBus, ACoilReplyShortOfItsRequestIsAFindingWithBothNumbers) {
  exchange(0x11, "01 00 00 00 11", "01 02 FF FF");  // 17 coils need 3 bytes
  finish();
  ASSERT_EQ(recorder_.frames.size(), 2u);
  const auto& m = recorder_.frames[1].mismatch;
  ASSERT_TRUE(m);
  EXPECT_EQ(m->expected, 3u);
  EXPECT_EQ(m->found, 2u);
}

TEST_F(ModbusBus, AQuantityOutOfRangeIsAFindingOnTheRequest) {
  exchange(0x11, "03 00 00 00 7E", "83 03");  // 126 registers: one more than allowed
  finish();
  ASSERT_EQ(recorder_.frames.size(), 2u);
  const auto& q = recorder_.frames[0].quantity;
  ASSERT_TRUE(q);
  EXPECT_EQ(q->found, 126u);
  EXPECT_EQ(q->max, 125u);
  EXPECT_EQ(recorder_.frames[1].request_id, 0u);
}

TEST_F(ModbusBus, AWriteWhoseByteCountDisagreesWithItsQuantityIsAFinding) {
  exchange(0x11, "10 00 0C 00 03 04 00 01 00 02", "90 03");  // 3 registers in 4 bytes
  exchange(0x11, "10 00 0C 00 02 04 00 01 00 02", "10 00 0C 00 02");
  const BusReport report = finish();
  ASSERT_EQ(recorder_.frames.size(), 4u);
  const auto& w = recorder_.frames[0].write_count;
  ASSERT_TRUE(w);
  EXPECT_EQ(w->byte_count, 4u);
  EXPECT_EQ(w->quantity, 3u);
  EXPECT_EQ(w->expected, 6u);
  EXPECT_FALSE(recorder_.frames[2].write_count);
  EXPECT_EQ(report.write_count_problems, 1u);
}

// A master's byte count of 0 before 6 data bytes, the CRC over all it sent: a malformed frame
// with a good check, paired with the exception that refused it; no noise.
TEST_F(ModbusBus, AWriteWhoseByteCountLiesIsAMalformedFramePairedWithItsReply) {
  exchange(0x11, "03 00 6B 00 01", "03 02 00 64");
  exchange(0x11, "10 00 0C 00 03 00 00 01 00 02 00 03", "90 03");
  const BusReport report = finish();
  ASSERT_EQ(recorder_.frames.size(), 4u);
  EXPECT_EQ(recorder_.noise_bytes, 0u);
  EXPECT_TRUE(recorder_.frames[2].check_ok);
  EXPECT_TRUE(recorder_.frames[2].malformed);
  EXPECT_EQ(recorder_.frames[2].role, Role::Request);
  EXPECT_EQ(recorder_.frames[3].request_id, 2u);
  ASSERT_TRUE(recorder_.frames[2].write_count);
  EXPECT_EQ(recorder_.frames[2].write_count->byte_count, 0u);
  EXPECT_EQ(report.unsolicited, 0u);
}

TEST_F(ModbusBus, ABroadcastWriteIsNeverATimeout) {
  send(adu(0x00, "06 00 01 00 03"));
  exchange(0x11, "03 00 6B 00 01", "03 02 00 64");
  finish();
  ASSERT_EQ(recorder_.frames.size(), 3u);
  EXPECT_TRUE(recorder_.timeouts.empty());
}

TEST_F(ModbusBus, ABroadcastReadIsAFindingNotATimeout) {
  send(adu(0x00, "03 00 00 00 02"));
  exchange(0x11, "03 00 6B 00 01", "03 02 00 64");
  const BusReport report = finish();
  ASSERT_EQ(recorder_.frames.size(), 3u);
  EXPECT_TRUE(recorder_.timeouts.empty());
  EXPECT_EQ(report.forbidden_broadcasts, 1u);
}

TEST_F(ModbusBus, AMeterBesideAGslInverterIsPlainModbus) {
  exchange(0x01, "03 04 1A 00 02", "03 04 08 FC 08 FD");  // GSL 1050..1051
  exchange(0x0A, "04 00 00 00 02", "04 04 43 66 19 9A");  // meter voltage, float32
  exchange(0x01, "03 04 1A 00 01", "83 02");              // GSL exception
  exchange(0x0A, "2B 0E 01 00",
           "2B 0E 01 01 00 00 02 00 07 45 41 53 54 52 4F 4E 01 06 53 44 4D 36 33 30");
  const BusReport report = finish();
  ASSERT_EQ(recorder_.frames.size(), 8u);
  EXPECT_EQ(recorder_.frames[0].dialect, Dialect::Gsl);
  EXPECT_EQ(recorder_.frames[1].dialect, Dialect::Gsl);
  EXPECT_EQ(recorder_.frames[2].dialect, Dialect::Modbus);
  EXPECT_EQ(recorder_.frames[3].dialect, Dialect::Modbus);
  EXPECT_EQ(recorder_.frames[5].dialect, Dialect::Gsl) << "an exception of a GSL station";
  EXPECT_EQ(recorder_.frames[7].dialect, Dialect::Modbus);
  ASSERT_EQ(report.stations.size(), 2u);
  EXPECT_EQ(report.stations[1].station, 0x0A);
  EXPECT_EQ(report.stations[1].device.vendor, "EASTRON");
  EXPECT_EQ(report.stations[1].device.product, "SDM630");
  EXPECT_EQ(report.stations[1].device.text(), "EASTRON SDM630");
  EXPECT_EQ(report.dialect_changes, 0u);
}

TEST_F(ModbusBus, AProbeOfAGslInverterWithAModbusCodeIsNoDialectChange) {
  exchange(0x01, "2B 0E 01 00", "AB 01");
  exchange(0x01, "03 04 1A 00 02", "03 04 08 FC 08 FD");
  exchange(0x01, "2B 0E 01 00", "AB 01");
  const BusReport report = finish();
  EXPECT_EQ(report.dialect_changes, 0u);
  EXPECT_EQ(recorder_.frames[2].dialect, Dialect::Gsl);
}

TEST_F(ModbusBus, AStationWhoseRequestsChangeDialectIsAFinding) {
  exchange(0x01, "03 04 1A 00 02", "03 04 08 FC 08 FD");  // GSL registers
  exchange(0x01, "03 00 00 00 02", "03 04 00 01 00 02");  // registers GSL does not have
  const BusReport report = finish();
  EXPECT_EQ(recorder_.frames[2].dialect, Dialect::Modbus);
  EXPECT_EQ(recorder_.frames[2].changed_from, Dialect::Gsl);
  EXPECT_EQ(report.dialect_changes, 1u);
  ASSERT_EQ(report.stations.size(), 1u);
  EXPECT_EQ(report.stations[0].dialect_changes, 1u);
}

// A real Fronius TS 65A-3 meter is read at 1024..1039, across GSL's alarm words 1030..1033.
TEST_F(ModbusBus, ARequestThatOnlyOverlapsGslRegistersIsPlainModbus) {
  exchange(0x01, "03 01 02 00 02", "03 04 00 01 00 02");
  std::string sixteen_words = "03 20";
  for (int i = 0; i < 32; ++i) sixteen_words += " 00";
  exchange(0x01, "03 04 00 00 10", sixteen_words);
  const BusReport report = finish();
  ASSERT_EQ(recorder_.frames.size(), 4u);
  for (const Seen& s : recorder_.frames) EXPECT_EQ(s.dialect, Dialect::Modbus);
  EXPECT_EQ(report.dialect_changes, 0u);
}

// Section 6: with nothing to go by, the earlier of gsl and modbus in --dialect's order.
TEST_F(ModbusBus, AReplyWithNothingToGoByTakesTheEarlierDialectOfTheList) {
  send(adu(0x05, "03 02 00 64"));
  BusSessionOptions options;
  options.reassembler.dialects = DialectSet::none().with(Dialect::Modbus).with(Dialect::Gsl);
  EXPECT_FALSE(options.reassembler.dialects.prefers_modbus());
  options.reassembler.dialects = options.reassembler.dialects.preferring_modbus();
  make(options);
  send(adu(0x05, "03 02 00 64"));
  finish();
  ASSERT_EQ(recorder_.frames.size(), 2u);
  EXPECT_EQ(recorder_.frames[0].dialect, Dialect::Gsl);
  EXPECT_EQ(recorder_.frames[1].dialect, Dialect::Modbus);
}

// A GSL request whose function code 0x03 was damaged into 0x02 stays its station's GSL.
TEST_F(ModbusBus, ADamagedFrameKeepsItsStationsDialect) {
  exchange(0x03, "03 04 1A 00 2E", "83 02");
  Bytes damaged = adu(0x03, "03 04 1A 00 2E");
  damaged[1] = 0x02;
  send(damaged);
  finish();
  ASSERT_EQ(recorder_.frames.size(), 3u);
  EXPECT_FALSE(recorder_.frames[2].check_ok);
  EXPECT_EQ(recorder_.frames[2].dialect, Dialect::Gsl);
}

TEST_F(ModbusBus, WithoutTheModbusDialectACoilReadIsNoise) {
  BusSessionOptions options;
  options.reassembler.dialects = DialectSet::none().with(Dialect::Gsl).with(Dialect::Hybrid);
  make(options);
  exchange(0x11, "01 00 13 00 13", "01 03 CD 6B 05");
  exchange(0x11, "03 00 6B 00 01", "03 02 00 64");
  finish();
  EXPECT_EQ(recorder_.frames.size(), 2u);
  EXPECT_EQ(recorder_.noise_bytes, 8u + 8u);
}

}  // namespace
}  // namespace pvtap
