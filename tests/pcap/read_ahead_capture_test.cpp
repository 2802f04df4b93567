// A capture read ahead on a second thread gives the records CaptureFile gives, in order:
// records larger than a batch, empty ones, cut ones, and a file that ends inside a record.
#include "pvtap/pcap/read_ahead_capture.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "pvtap/pcap/capture_file.h"
#include "pvtap/pcap/link_types.h"
#include "pvtap/pcap/pcap_writer.h"

namespace pvtap {
namespace {

struct Record {
  double time;
  std::vector<std::uint8_t> bytes;
  std::uint32_t length_on_wire;
  bool operator==(const Record&) const = default;
};

std::string temp_path(const char* name) {
  return std::string(::testing::TempDir()) + name;
}

// Records up to libpcap's largest (256 KiB for Ethernet) in an order that crosses several
// batches and makes one record overflow a batch's buffer (620 x 1500 bytes, then 256 KiB).
constexpr std::size_t kLargest = 262144;

std::vector<std::size_t> record_sizes() {
  std::vector<std::size_t> sizes(620, 1500);
  sizes.push_back(kLargest);
  for (std::size_t i = 0; i < 3000; ++i) sizes.push_back(i * 37 % 1500);
  sizes.push_back(0);
  for (int i = 0; i < 5; ++i) sizes.push_back(kLargest);
  for (std::size_t i = 0; i < 2000; ++i) sizes.push_back(60 + i % 9);
  return sizes;
}

std::string write_capture(const char* name) {
  const std::string path = temp_path(name);
  PcapWriter writer;
  EXPECT_TRUE(writer.open(path, dlt::kEthernet, static_cast<int>(kLargest))) << writer.error();
  std::int64_t micros = 1790000000000000;
  for (const std::size_t size : record_sizes()) {
    std::vector<std::uint8_t> bytes(size);
    for (std::size_t i = 0; i < size; ++i) bytes[i] = static_cast<std::uint8_t>(i * 7 + size);
    micros += 1 + static_cast<std::int64_t>(size % 1000);
    writer.write(micros, bytes, size % 5 == 0 ? static_cast<std::uint32_t>(size + 3) : 0);
  }
  EXPECT_TRUE(writer.close());
  return path;
}

template <typename Reader>
std::vector<Record> read_all(Reader& reader, CaptureFile::Next& end) {
  std::vector<Record> records;
  CapturedPacket packet;
  for (;;) {
    end = reader.next(packet);
    if (end != CaptureFile::Next::Packet) return records;
    records.push_back(
        Record{packet.time, {packet.bytes.begin(), packet.bytes.end()}, packet.length_on_wire});
    EXPECT_EQ(reader.packets(), records.size());
  }
}

void expect_same_as_capture_file(const std::string& path, bool read_ahead) {
  CaptureFile file;
  ASSERT_TRUE(file.open(path)) << file.error();
  CaptureFile::Next file_end{};
  const std::vector<Record> expected = read_all(file, file_end);

  ReadAheadCapture reader(read_ahead);
  ASSERT_TRUE(reader.open(path)) << reader.error();
  EXPECT_EQ(reader.link_type(), dlt::kEthernet);
  CaptureFile::Next end{};
  const std::vector<Record> records = read_all(reader, end);
  EXPECT_EQ(end, file_end);
  EXPECT_EQ(reader.error(), file.error());
  EXPECT_EQ(reader.position(), file.position());
  ASSERT_EQ(records.size(), expected.size());
  for (std::size_t i = 0; i < records.size(); ++i) ASSERT_EQ(records[i], expected[i]) << i;
  // Asking again after the end gives the end again.
  CapturedPacket packet;
  EXPECT_EQ(reader.next(packet), file_end);
}

TEST(ReadAheadCapture, GivesEveryRecordInOrderAcrossBatches) {
  const std::string path = write_capture("pvtap_read_ahead.pcap");
  expect_same_as_capture_file(path, true);
  expect_same_as_capture_file(path, false);
  ReadAheadCapture reader(true);
  ASSERT_TRUE(reader.open(path));
  CaptureFile::Next end{};
  EXPECT_EQ(read_all(reader, end).size(), record_sizes().size());
  EXPECT_EQ(end, CaptureFile::Next::End);
  EXPECT_GT(reader.position(), 3 * ReadAheadCapture::kBatchBytes);
}

TEST(ReadAheadCapture, AFileCutInsideARecordEndsTruncatedAfterTheRecordsBefore) {
  const std::string path = write_capture("pvtap_read_ahead_cut.pcap");
  std::FILE* f = std::fopen(path.c_str(), "r+b");
  ASSERT_NE(f, nullptr);
  std::fseek(f, 0, SEEK_END);
  const long size = std::ftell(f);
  std::fclose(f);
  ASSERT_EQ(::truncate(path.c_str(), size - 30), 0);
  expect_same_as_capture_file(path, true);
  CaptureFile file;
  ASSERT_TRUE(file.open(path));
  CaptureFile::Next end{};
  read_all(file, end);
  EXPECT_EQ(end, CaptureFile::Next::Truncated);
}

TEST(ReadAheadCapture, StoppingEarlyEndsTheReadingThread) {
  const std::string path = write_capture("pvtap_read_ahead_early.pcap");
  ReadAheadCapture reader(true);
  ASSERT_TRUE(reader.open(path));
  CapturedPacket packet;
  for (int i = 0; i < 10; ++i) ASSERT_EQ(reader.next(packet), CaptureFile::Next::Packet);
  // The destructor stops the thread, which may be waiting for a free batch.
}

TEST(ReadAheadCapture, AMissingFileSaysWhy) {
  ReadAheadCapture reader(true);
  EXPECT_FALSE(reader.open(temp_path("pvtap_no_such_capture.pcap")));
  EXPECT_NE(reader.error().find("No such file"), std::string::npos) << reader.error();
}

}  // namespace
}  // namespace pvtap
