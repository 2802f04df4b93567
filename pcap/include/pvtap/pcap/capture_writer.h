// CaptureWriter: where generated capture records go, as pcap (through libpcap) or pcapng
// (libpcap cannot write pcapng); for the simulator, the test captures and the benchmarks.
#pragma once

#include <cstdint>
#include <cstdio>
#include <memory>
#include <span>
#include <string>

#include "pvtap/pcap/pcap_writer.h"

namespace pvtap {

class CaptureWriter {
 public:
  virtual ~CaptureWriter() = default;
  // `length_on_wire` 0 means the record is whole.
  virtual void write(double time, std::span<const std::uint8_t> bytes,
                     std::uint32_t length_on_wire = 0) = 0;
};

// PcapCaptureWriter: a classic pcap file (microsecond timestamps) of one link type.
class PcapCaptureWriter : public CaptureWriter {
 public:
  // Throws std::runtime_error when the file cannot be created.
  PcapCaptureWriter(const std::string& path, int link_type, int snap_length = 65535);
  void write(double time, std::span<const std::uint8_t> bytes,
             std::uint32_t length_on_wire = 0) override;

 private:
  PcapWriter file_;
};

// PcapngCaptureWriter: a pcapng file with one interface (section header, interface
// description, enhanced packet blocks; microsecond timestamps).
class PcapngCaptureWriter : public CaptureWriter {
 public:
  // Throws std::runtime_error when the file cannot be created.
  PcapngCaptureWriter(const std::string& path, int link_type);
  ~PcapngCaptureWriter() override;
  PcapngCaptureWriter(const PcapngCaptureWriter&) = delete;
  PcapngCaptureWriter& operator=(const PcapngCaptureWriter&) = delete;
  void write(double time, std::span<const std::uint8_t> bytes,
             std::uint32_t length_on_wire = 0) override;

 private:
  std::FILE* file_ = nullptr;
};

std::unique_ptr<CaptureWriter> open_capture_writer(const std::string& path, int link_type,
                                                   bool pcapng);

}  // namespace pvtap
