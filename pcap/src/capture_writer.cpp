#include "pvtap/pcap/capture_writer.h"

#include <cmath>
#include <stdexcept>
#include <vector>

namespace pvtap {
namespace {

void split_time(double time, std::uint64_t& seconds, std::uint32_t& micros) {
  const auto total = static_cast<std::uint64_t>(std::llround(time * 1e6));
  seconds = total / 1000000;
  micros = static_cast<std::uint32_t>(total % 1000000);
}

void put32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<std::uint8_t>(v >> (8 * i)));  // LE
}

void put16(std::vector<std::uint8_t>& out, std::uint16_t v) {
  out.push_back(static_cast<std::uint8_t>(v));
  out.push_back(static_cast<std::uint8_t>(v >> 8));
}

// Wraps a block body in its type and both length fields (pcapng blocks are 32-bit aligned).
void write_block(std::FILE* f, std::uint32_t type, std::vector<std::uint8_t> body) {
  while (body.size() % 4 != 0) body.push_back(0);
  const auto total = static_cast<std::uint32_t>(body.size() + 12);
  std::vector<std::uint8_t> block;
  put32(block, type);
  put32(block, total);
  block.insert(block.end(), body.begin(), body.end());
  put32(block, total);
  std::fwrite(block.data(), 1, block.size(), f);
}

}  // namespace

PcapCaptureWriter::PcapCaptureWriter(const std::string& path, int link_type, int snap_length) {
  if (!file_.open(path, link_type, snap_length)) {
    throw std::runtime_error("cannot write " + path + ": " + file_.error());
  }
}

void PcapCaptureWriter::write(double time, std::span<const std::uint8_t> bytes,
                              std::uint32_t length_on_wire) {
  file_.write(std::llround(time * 1e6), bytes, length_on_wire);
}

PcapngCaptureWriter::PcapngCaptureWriter(const std::string& path, int link_type) {
  file_ = std::fopen(path.c_str(), "wb");
  if (file_ == nullptr) throw std::runtime_error("cannot write " + path);
  std::vector<std::uint8_t> shb;
  put32(shb, 0x1A2B3C4D);  // byte-order magic
  put16(shb, 1);           // version 1.0
  put16(shb, 0);
  put32(shb, 0xFFFFFFFF);  // section length unknown
  put32(shb, 0xFFFFFFFF);
  write_block(file_, 0x0A0D0D0A, shb);
  std::vector<std::uint8_t> idb;
  put16(idb, static_cast<std::uint16_t>(link_type));
  put16(idb, 0);
  put32(idb, 65535);  // snap length; no options: timestamps in microseconds
  write_block(file_, 0x00000001, idb);
}

PcapngCaptureWriter::~PcapngCaptureWriter() {
  std::fclose(file_);
}

void PcapngCaptureWriter::write(double time, std::span<const std::uint8_t> bytes,
                                std::uint32_t length_on_wire) {
  std::uint64_t seconds = 0;
  std::uint32_t micros = 0;
  split_time(time, seconds, micros);
  const std::uint64_t ticks = seconds * 1000000 + micros;
  std::vector<std::uint8_t> epb;
  put32(epb, 0);  // interface 0
  put32(epb, static_cast<std::uint32_t>(ticks >> 32));
  put32(epb, static_cast<std::uint32_t>(ticks));
  put32(epb, static_cast<std::uint32_t>(bytes.size()));
  put32(epb, length_on_wire != 0 ? length_on_wire : static_cast<std::uint32_t>(bytes.size()));
  epb.insert(epb.end(), bytes.begin(), bytes.end());
  write_block(file_, 0x00000006, epb);
}

std::unique_ptr<CaptureWriter> open_capture_writer(const std::string& path, int link_type,
                                                   bool pcapng) {
  if (pcapng) return std::make_unique<PcapngCaptureWriter>(path, link_type);
  return std::make_unique<PcapCaptureWriter>(path, link_type);
}

}  // namespace pvtap
