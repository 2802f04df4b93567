// PcapWriter: a pcap file of one link type written through libpcap (pcap_open_dead +
// pcap_dump), one record at a time; shared by the analyzer's --write, the
// simulator and the test captures.
#pragma once

#include <cstdint>
#include <span>
#include <string>

typedef struct pcap pcap_t;
typedef struct pcap_dumper pcap_dumper_t;

namespace pvtap {

class PcapWriter {
 public:
  PcapWriter() = default;
  ~PcapWriter();
  PcapWriter(const PcapWriter&) = delete;
  PcapWriter& operator=(const PcapWriter&) = delete;

  // Creates the file; false with error() set when it cannot be written.
  bool open(const std::string& path, int link_type, int snap_length = 65535);
  // One record stamped `micros` microseconds after the Unix epoch, `length_on_wire` when it
  // was cut (0: whole); nothing when not open.
  void write(std::int64_t micros, std::span<const std::uint8_t> record,
             std::uint32_t length_on_wire = 0);
  // Pushes written records to the file (live capture: an abrupt end then loses nothing).
  bool flush();
  // Flushes and closes; false when writing failed.
  bool close();
  bool is_open() const { return dumper_ != nullptr; }
  const std::string& error() const { return error_; }

 private:
  pcap_t* pcap_ = nullptr;
  pcap_dumper_t* dumper_ = nullptr;
  std::string error_;
};

}  // namespace pvtap
