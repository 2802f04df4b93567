// Serial records (RTAC), exported PDUs (link type 252) written and read back through libpcap.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "pvtap/pcap/capture_file.h"
#include "pvtap/pcap/exported_pdu_reader.h"
#include "pvtap/pcap/exported_pdu_writer.h"
#include "pvtap/pcap/link_types.h"
#include "pvtap/pcap/rtac_record.h"

namespace pvtap::analyzer {
namespace {

using Bytes = std::vector<std::uint8_t>;

std::string temp_path(const char* name) {
  return std::string(::testing::TempDir()) + name;
}

TEST(SerialRecords, RtacHeaderIsSkippedAndDataLossIsSeen) {
  Bytes record = {0x6A, 0xB1, 0x2C, 0x00, 0x00, 0x01, 0x00,
                  0x00, 0x02, 0x19, 0x00, 0x00, 0x01, 0x03};
  auto r = rtac_serial_record(record);
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(Bytes(r->bytes.begin(), r->bytes.end()), (Bytes{0x01, 0x03}));
  EXPECT_FALSE(r->data_lost_before);
  record[8] = 0x05;  // CAPTURE_DATA_LOST
  EXPECT_TRUE(rtac_serial_record(record)->data_lost_before);
  EXPECT_FALSE(rtac_serial_record(Bytes(11, 0)).has_value());
}

TEST(ExportedPdu, TagsAreReadWhateverTheirOrder) {
  const Bytes record = {
      0x00, 0x23, 0x00, 0x04, 0x00, 0x00, 0x00, 0x01,  // direction: received
      0x00, 0x0C, 0x00, 0x08, 'p',  'v',  't',  'a',  'p',
      0,    0,    0,    0x00, 0x63, 0x00, 0x01, 0x7F,  // an unknown tag is skipped
      0x00, 0x00, 0x00, 0x00,                          // end
      0x01, 0x03};
  auto pdu = exported_pdu_record(record);
  ASSERT_TRUE(pdu.has_value());
  EXPECT_EQ(pdu->dissector, "pvtap");
  EXPECT_EQ(pdu->direction, Direction::FromSlave);
  EXPECT_EQ(Bytes(pdu->pdu.begin(), pdu->pdu.end()), (Bytes{0x01, 0x03}));
  EXPECT_FALSE(exported_pdu_record(Bytes{0x00, 0x0C, 0x00, 0x08, 'p'}).has_value());
  EXPECT_FALSE(exported_pdu_record(Bytes{0x00, 0x0C, 0x00, 0x00}).has_value());  // no end tag
}

TEST(ExportedPdu, WrittenFileReadsBackWithTagsAndTimes) {
  const std::string path = temp_path("pvtap_written.pcap");
  const Bytes request = {0x01, 0x03, 0x00, 0x00, 0x00, 0x0A, 0xC5, 0xCD};
  const Bytes reply = {0x01, 0x03, 0x02, 0x00, 0x07, 0xF9, 0x86};
  {
    ExportedPduWriter writer;
    ASSERT_TRUE(writer.open(path)) << writer.error();
    writer.write_frame(1790000000.25, Role::Request, request);
    writer.write_frame(1790000000.5, Role::Response, reply);
    writer.write_noise(1790000000.75, Direction::Unknown, std::vector<std::uint8_t>{0x00});
    ASSERT_TRUE(writer.close());
    EXPECT_EQ(writer.records(), 3u);
  }
  CaptureFile file;
  ASSERT_TRUE(file.open(path)) << file.error();
  EXPECT_EQ(file.link_type(), dlt::kUpperPdu);
  EXPECT_EQ(input_kind_of(file.link_type()), InputKind::ExportedPdu);
  CapturedPacket packet;
  ASSERT_EQ(file.next(packet), CaptureFile::Next::Packet);
  EXPECT_DOUBLE_EQ(packet.time, 1790000000.25);
  auto first = exported_pdu_record(packet.bytes);
  ASSERT_TRUE(first.has_value());
  EXPECT_EQ(first->dissector, "pvtap");
  EXPECT_EQ(first->direction, Direction::ToSlave);
  EXPECT_EQ(Bytes(first->pdu.begin(), first->pdu.end()), request);
  // The dissector name tag is padded to four bytes, as Wireshark writes it.
  EXPECT_EQ(Bytes(packet.bytes.begin(), packet.bytes.begin() + 12),
            (Bytes{0x00, 0x0C, 0x00, 0x08, 'p', 'v', 't', 'a', 'p', 0, 0, 0}));
  ASSERT_EQ(file.next(packet), CaptureFile::Next::Packet);
  EXPECT_EQ(exported_pdu_record(packet.bytes)->direction, Direction::FromSlave);
  ASSERT_EQ(file.next(packet), CaptureFile::Next::Packet);
  EXPECT_EQ(exported_pdu_record(packet.bytes)->direction, Direction::Unknown);  // no tag
  EXPECT_EQ(packet.bytes.size(), 12u + 4u + 1u);
  EXPECT_EQ(file.next(packet), CaptureFile::Next::End);
  std::remove(path.c_str());
}

TEST(ExportedPdu, PvtapRecordsCarryTheirRunsFactsExactly) {
  const std::string path = temp_path("pvtap_facts.pcap");
  const Bytes reply = {0x01, 0x03, 0x02, 0x00, 0x07, 0xF9, 0x87};  // its check damaged
  // Times no microsecond stamp holds: the tag keeps every bit of them.
  const RecordFacts frame{
      RecordKind::Frame, Direction::Unknown, 1790000000.1234567, 1790000000.1307481, {}};
  const RecordFacts noise{RecordKind::Noise, Direction::FromSlave, 1790000000.2, 1790000000.21, {}};
  const RunFacts run{DialectSet::only(Dialect::Gsl).with(Dialect::Modbus).preferring_modbus(),
                     19200, 0.4, "10.0.0.2:4001"};
  {
    ExportedPduWriter writer;
    ASSERT_TRUE(writer.open(path)) << writer.error();
    writer.write_record(frame, &run, Direction::FromSlave, reply);
    writer.write_record(noise, nullptr, Direction::FromSlave, Bytes{0xFF, 0x00});
    writer.write_loss(1790000001.25, Direction::ToSlave, 51, nullptr);
    writer.write_loss(1790000001.375, Direction::Unknown, std::nullopt, nullptr);
    writer.write_end(1790000001.5);
    ASSERT_TRUE(writer.close());
  }
  CaptureFile file;
  ASSERT_TRUE(file.open(path)) << file.error();
  CapturedPacket packet;
  ASSERT_EQ(file.next(packet), CaptureFile::Next::Packet);
  EXPECT_DOUBLE_EQ(packet.time, 1790000000.130748);  // stamped at the last byte, as before
  auto first = exported_pdu_record(packet.bytes);
  ASSERT_TRUE(first.has_value());
  const auto first_facts = record_facts(first->pvtap_record);
  const auto first_run = run_facts(first->pvtap_run);
  ASSERT_TRUE(first_facts && first_run);
  EXPECT_EQ(first->dissector, "pvtap");
  EXPECT_EQ(first->direction, Direction::FromSlave);
  EXPECT_EQ(first_facts->kind, RecordKind::Frame);
  EXPECT_EQ(first_facts->stream, Direction::Unknown);
  EXPECT_EQ(first_facts->start_time, frame.start_time);
  EXPECT_EQ(first_facts->end_time, frame.end_time);
  EXPECT_EQ(first_run->dialects, run.dialects);
  EXPECT_EQ(first_run->baud, 19200u);
  EXPECT_EQ(first_run->timeout, 0.4);
  EXPECT_EQ(first_run->bus, "10.0.0.2:4001");
  EXPECT_EQ(Bytes(first->pdu.begin(), first->pdu.end()), reply);
  ASSERT_EQ(file.next(packet), CaptureFile::Next::Packet);
  auto second = exported_pdu_record(packet.bytes);
  ASSERT_TRUE(second && record_facts(second->pvtap_record));
  EXPECT_EQ(record_facts(second->pvtap_record)->kind, RecordKind::Noise);
  EXPECT_EQ(record_facts(second->pvtap_record)->stream, Direction::FromSlave);
  EXPECT_TRUE(second->pvtap_run.empty()) << "the run's tag only where the bus changes";
  for (const std::optional<std::uint64_t> lost : {std::optional<std::uint64_t>{51}, {}}) {
    ASSERT_EQ(file.next(packet), CaptureFile::Next::Packet);
    const auto loss = record_facts(exported_pdu_record(packet.bytes)->pvtap_record);
    ASSERT_TRUE(loss.has_value());
    EXPECT_EQ(loss->kind, RecordKind::Loss);
    EXPECT_EQ(loss->lost_bytes, lost);
    // A mark of a moment, not bus bytes: another dissector, and a line saying what it marks.
    EXPECT_EQ(exported_pdu_record(packet.bytes)->dissector, exported_pdu::kEventDissectorName);
    const auto text = exported_pdu_record(packet.bytes)->pdu;
    EXPECT_EQ(std::string(text.begin(), text.end()),
              lost ? "capture data lost of the master's side: 51 bytes"
                   : "capture data lost: bytes unknown");
  }
  ASSERT_EQ(file.next(packet), CaptureFile::Next::Packet);
  auto end = exported_pdu_record(packet.bytes);
  ASSERT_TRUE(end && record_facts(end->pvtap_record));
  EXPECT_EQ(record_facts(end->pvtap_record)->kind, RecordKind::End);
  EXPECT_EQ(record_facts(end->pvtap_record)->end_time, 1790000001.5);
  EXPECT_EQ(end->dissector, exported_pdu::kEventDissectorName);
  EXPECT_EQ(std::string(end->pdu.begin(), end->pdu.end()),
            "end of the run: requests still waiting were judged here");
  EXPECT_EQ(file.next(packet), CaptureFile::Next::End);
  std::remove(path.c_str());
}

TEST(ExportedPdu, PvtapTagsOfAnotherVersionAreLeftUnread) {
  Bytes record = {0x70, 0x76, 0x00, 0x14, 0x02, 0x01, 0x00, 0x00};  // version 2
  record.resize(4 + 20, 0);
  const Bytes tail = {0x00, 0x0C, 0x00, 0x05, 'p',  'v',  't', 'a',
                      'p',  0x00, 0x00, 0x00, 0x00, 0x01, 0x03};
  record.insert(record.end(), tail.begin(), tail.end());
  const auto facts_of = [](const Bytes& r) {
    return record_facts(exported_pdu_record(r)->pvtap_record);
  };
  auto pdu = exported_pdu_record(record);
  ASSERT_TRUE(pdu.has_value());
  EXPECT_FALSE(facts_of(record).has_value());
  EXPECT_EQ(pdu->dissector, "pvtap");
  record[4] = 0x01;  // version 1, but kind 9
  record[5] = 0x09;
  EXPECT_FALSE(facts_of(record).has_value());
  record[5] = 0x02;
  ASSERT_TRUE(facts_of(record).has_value());
  EXPECT_EQ(facts_of(record)->kind, RecordKind::Noise);
  EXPECT_FALSE(run_facts(pdu->pvtap_run).has_value()) << "no run tag";
}

TEST(CaptureFile, TellsWhatIsWrongWithAFile) {
  CaptureFile missing;
  EXPECT_FALSE(missing.open(temp_path("pvtap_no_such_file.pcap")));
  EXPECT_EQ(missing.error(), "No such file or directory");
  const std::string text = temp_path("pvtap_text.pcap");
  std::FILE* f = std::fopen(text.c_str(), "w");
  std::fputs("not a capture at all\n", f);
  std::fclose(f);
  CaptureFile not_capture;
  EXPECT_FALSE(not_capture.open(text));
  EXPECT_NE(not_capture.error().find("not a pcap or pcapng capture"), std::string::npos);
  std::remove(text.c_str());
}

TEST(LinkTypes, KindsAndTheSupportedList) {
  EXPECT_EQ(input_kind_of(dlt::kEthernet), InputKind::Network);
  EXPECT_EQ(input_kind_of(dlt::kLinuxSll2), InputKind::Network);
  EXPECT_EQ(input_kind_of(dlt::kUser0 + 5), InputKind::Serial);
  EXPECT_EQ(input_kind_of(dlt::kRtacSerial), InputKind::RtacSerial);
  EXPECT_FALSE(input_kind_of(105).has_value());  // 802.11
  EXPECT_NE(supported_link_types_text().find("USER0-USER15"), std::string::npos);
}

}  // namespace
}  // namespace pvtap::analyzer
