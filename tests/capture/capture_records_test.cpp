// Serial records (RTAC), exported PDUs (link type 252) written and read back through libpcap.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "pvtap/capture/capture_file.h"
#include "pvtap/capture/exported_pdu_writer.h"
#include "pvtap/capture/link_types.h"
#include "pvtap/capture/exported_pdu_reader.h"
#include "pvtap/capture/rtac_record.h"

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
