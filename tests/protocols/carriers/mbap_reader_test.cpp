// MbapReader: ADUs out of one direction of a TCP flow cut anywhere, every byte accounted for,
// and the resynchronisation after a header that lied.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "hex_bytes.h"
#include "pvtap/carriers/mbap_reader.h"
#include "pvtap/carriers/mbap_structure.h"

namespace pvtap {
namespace {

using Bytes = std::vector<std::uint8_t>;

// An ADU of transaction `tid` to `unit` carrying the PDU in hex, with a length that holds.
Bytes adu(std::uint16_t tid, std::uint8_t unit, std::string_view pdu) {
  const Bytes body = test::hex_bytes(pdu);
  const std::size_t length = body.size() + 1;
  Bytes out;
  for (const std::size_t field : {std::size_t{tid}, std::size_t{0}, length}) {
    out.push_back(static_cast<std::uint8_t>(field >> 8));
    out.push_back(static_cast<std::uint8_t>(field & 0xFF));
  }
  out.push_back(unit);
  for (const std::uint8_t b : body) out.push_back(b);
  return out;
}

Bytes join(std::initializer_list<Bytes> parts) {
  Bytes out;
  for (const Bytes& p : parts) out.insert(out.end(), p.begin(), p.end());
  return out;
}

struct Recorder : MbapSink {
  void on_adu(const MbapAdu& a) override {
    tids.push_back(a.transaction);
    units.push_back(a.unit);
    frames.emplace_back(a.frame.begin(), a.frame.end());
    offsets.push_back(a.offset);
  }
  void on_finding(const MbapFinding& f) override { findings.push_back(f); }
  std::vector<std::uint16_t> tids;
  std::vector<std::uint8_t> units;
  std::vector<Bytes> frames;
  std::vector<std::uint64_t> offsets;
  std::vector<MbapFinding> findings;
};

void expect_accounted(const MbapReader& r) {
  const MbapTotals& t = r.totals();
  EXPECT_EQ(t.bytes_in, t.carrier_bytes + t.frame_bytes + t.skipped_bytes + r.pending_bytes());
}

TEST(MbapReader, TwoAdusInOnePieceAndOneSplitOverThree) {
  Recorder rec;
  MbapReader reader(rec);
  const Bytes both = join({adu(1, 5, "03 00 00 00 02"), adu(2, 6, "04 00 10 00 01")});
  reader.feed(both, 1.0);
  const Bytes split = adu(3, 7, "03 04 01 02 03 04");
  reader.feed({split.data(), 3}, 1.1);  // inside the header
  reader.feed({split.data() + 3, 6}, 1.2);
  EXPECT_EQ(rec.tids.size(), 2u);
  reader.feed({split.data() + 9, split.size() - 9}, 1.3);
  ASSERT_EQ(rec.tids, (std::vector<std::uint16_t>{1, 2, 3}));
  EXPECT_EQ(rec.units, (std::vector<std::uint8_t>{5, 6, 7}));
  EXPECT_EQ(rec.frames[2], test::hex_bytes("07 03 04 01 02 03 04"));
  EXPECT_EQ(rec.offsets, (std::vector<std::uint64_t>{0, 12, 24}));
  EXPECT_TRUE(rec.findings.empty());
  EXPECT_EQ(reader.totals().carrier_bytes, 18u);
  EXPECT_EQ(reader.totals().frame_bytes, 7u + 6u + 7u - 1u);
  EXPECT_EQ(reader.pending_bytes(), 0u);
  expect_accounted(reader);
}

TEST(MbapReader, ProtocolIdNotZeroGivesUpTheRestOfItsPiece) {
  Recorder rec;
  MbapReader reader(rec);
  Bytes bad = join({adu(1, 1, "03 00 00 00 01"), adu(2, 1, "03 00 00 00 01")});
  bad[3] = 0x01;  // protocol id 1
  reader.feed(bad, 1.0);
  reader.feed(adu(3, 1, "03 00 00 00 01"), 1.1);
  ASSERT_EQ(rec.findings.size(), 1u);
  EXPECT_EQ(rec.findings[0].problem, MbapProblem::ProtocolId);
  EXPECT_EQ(rec.findings[0].protocol_id, 1u);
  EXPECT_EQ(rec.findings[0].skipped, 24u);
  EXPECT_EQ(rec.tids, (std::vector<std::uint16_t>{3}));
  EXPECT_EQ(reader.totals().skipped_bytes, 24u);
  expect_accounted(reader);
}

TEST(MbapReader, LengthsThatCannotBeTrue) {
  Recorder rec;
  MbapReader reader(rec);
  Bytes short_one = adu(1, 1, "03 00 00 00 01");
  short_one[5] = 1;  // no room for a function code
  reader.feed(short_one, 1.0);
  Bytes long_one = adu(2, 1, "03 00 00 00 01");
  long_one[4] = 0x01;  // 0x0106: longer than any ADU
  reader.feed(long_one, 1.1);
  ASSERT_EQ(rec.findings.size(), 2u);
  EXPECT_EQ(rec.findings[0].problem, MbapProblem::LengthTooShort);
  EXPECT_EQ(rec.findings[0].declared_length, 1u);
  EXPECT_EQ(rec.findings[1].problem, MbapProblem::LengthTooLong);
  EXPECT_EQ(rec.findings[1].declared_length, 0x0106u);
  EXPECT_EQ(rec.findings[1].skipped, 12u);
  EXPECT_TRUE(rec.tids.empty());
  expect_accounted(reader);
}

TEST(MbapReader, ALengthThatOverrunsIsFoundByTheNextPiece) {
  Recorder rec;
  MbapReader reader(rec);
  Bytes liar = adu(1, 1, "03 00 00 00 01");
  liar[5] = 20;  // says 20, carries 6
  reader.feed(liar, 1.0);
  EXPECT_TRUE(rec.findings.empty());  // TCP may split an ADU: it waits
  reader.feed(adu(2, 1, "03 00 00 00 01"), 1.1);
  ASSERT_EQ(rec.findings.size(), 1u);
  EXPECT_EQ(rec.findings[0].problem, MbapProblem::LengthOverruns);
  EXPECT_EQ(rec.findings[0].declared_length, 20u);
  EXPECT_EQ(rec.findings[0].skipped, 12u);
  EXPECT_EQ(rec.findings[0].offset, 0u);
  EXPECT_EQ(rec.tids, (std::vector<std::uint16_t>{2}));
  EXPECT_EQ(rec.offsets, (std::vector<std::uint64_t>{12}));
  expect_accounted(reader);
}

TEST(MbapReader, ASplitAduWhoseRestIsNotWholeAdusIsBelieved) {
  Recorder rec;
  MbapReader reader(rec);
  const Bytes reply = adu(9, 2, "03 08 00 00 00 00 00 00 00 00");
  reader.feed({reply.data(), 10}, 1.0);
  reader.feed({reply.data() + 10, reply.size() - 10}, 1.1);
  EXPECT_TRUE(rec.findings.empty());
  EXPECT_EQ(rec.tids, (std::vector<std::uint16_t>{9}));
  expect_accounted(reader);
}

TEST(MbapReader, TheEndOfTheFlowGivesUpAnUnfinishedAdu) {
  Recorder rec;
  MbapReader reader(rec);
  const Bytes one = adu(1, 1, "03 00 00 00 01");
  reader.feed({one.data(), 8}, 1.0);
  EXPECT_EQ(reader.pending_bytes(), 8u);
  expect_accounted(reader);
  reader.finish(2.0);
  ASSERT_EQ(rec.findings.size(), 1u);
  EXPECT_EQ(rec.findings[0].problem, MbapProblem::Truncated);
  EXPECT_EQ(rec.findings[0].skipped, 8u);
  EXPECT_EQ(reader.pending_bytes(), 0u);
  expect_accounted(reader);
}

TEST(MbapStructure, WholeAdusOnly) {
  EXPECT_TRUE(whole_mbap_adus(adu(1, 1, "03 00 00 00 01")));
  EXPECT_TRUE(whole_mbap_adus(join({adu(1, 1, "03 00 00 00 01"), adu(2, 1, "83 02")})));
  Bytes cut = adu(1, 1, "03 00 00 00 01");
  cut.pop_back();
  EXPECT_FALSE(whole_mbap_adus(cut));
  Bytes trailing = adu(1, 1, "03 00 00 00 01");
  trailing.push_back(0);
  EXPECT_FALSE(whole_mbap_adus(trailing));
  EXPECT_FALSE(whole_mbap_adus(adu(1, 1, "00 00 00 00 01")));  // function code 0
  // An RTU frame is not MBAP: its third and fourth bytes are rarely both 0.
  EXPECT_FALSE(whole_mbap_adus(test::hex_bytes("01 03 00 00 00 0A C5 CD")));
  EXPECT_FALSE(whole_mbap_adus({}));
}

}  // namespace
}  // namespace pvtap
