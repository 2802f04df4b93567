// Capture files written by the test generator: pcap through libpcap's pcap_dump, and a
// minimal pcapng writer (libpcap cannot write pcapng).
#pragma once

#include <cstdint>
#include <cstdio>
#include <memory>
#include <span>
#include <string>

typedef struct pcap pcap_t;
typedef struct pcap_dumper pcap_dumper_t;

namespace pvtap::forge {

// CaptureOut: where generated records go.
class CaptureOut {
 public:
  virtual ~CaptureOut() = default;
  // `length_on_wire` 0 means the record is whole.
  virtual void write(double time, std::span<const std::uint8_t> bytes,
                     std::uint32_t length_on_wire = 0) = 0;
};

// PcapOut: a classic pcap file (microsecond timestamps) of one link type.
class PcapOut : public CaptureOut {
 public:
  PcapOut(const std::string& path, int link_type, int snap_length = 65535);
  ~PcapOut() override;
  void write(double time, std::span<const std::uint8_t> bytes,
             std::uint32_t length_on_wire = 0) override;

 private:
  pcap_t* pcap_ = nullptr;
  pcap_dumper_t* dumper_ = nullptr;
};

// PcapngOut: a pcapng file with one interface (section header, interface description,
// enhanced packet blocks; microsecond timestamps).
class PcapngOut : public CaptureOut {
 public:
  PcapngOut(const std::string& path, int link_type);
  ~PcapngOut() override;
  void write(double time, std::span<const std::uint8_t> bytes,
             std::uint32_t length_on_wire = 0) override;

 private:
  std::FILE* file_ = nullptr;
};

std::unique_ptr<CaptureOut> open_capture(const std::string& path, int link_type, bool pcapng);

}  // namespace pvtap::forge
