// PcapFile: a pcap being written through libpcap (pcap_open_dead + pcap_dump), one record at
// a time, with simulated timestamps.
#pragma once

#include <cstdint>
#include <span>
#include <string>

#include "bus_event.h"

typedef struct pcap pcap_t;
typedef struct pcap_dumper pcap_dumper_t;

namespace pvtap::sim {

class PcapFile {
 public:
  PcapFile() = default;
  ~PcapFile();
  PcapFile(const PcapFile&) = delete;
  PcapFile& operator=(const PcapFile&) = delete;

  bool open(const std::string& path, int link_type);
  void write(Micros time, std::span<const std::uint8_t> record);
  bool close();
  const std::string& error() const { return error_; }

 private:
  pcap_t* pcap_ = nullptr;
  pcap_dumper_t* dumper_ = nullptr;
  std::string error_;
};

}  // namespace pvtap::sim
