// CaptureFile: one pcap or pcapng file read record by record through libpcap.
#pragma once

#include <cstdint>
#include <cstdio>
#include <span>
#include <string>

typedef struct pcap pcap_t;
struct pcap_pkthdr;

namespace pvtap {

// CapturedPacket: one record; `bytes` is valid until the next call to next().
struct CapturedPacket {
  double time = 0;  // seconds since the epoch, nanosecond resolution when the file has it
  std::span<const std::uint8_t> bytes;
  std::uint32_t length_on_wire = 0;
};

// The packet of a libpcap record; `nanoseconds` when the handle was opened with nanosecond
// precision (libpcap then puts nanoseconds in tv_usec).
CapturedPacket packet_of(const pcap_pkthdr& header, const unsigned char* data, bool nanoseconds);

class CaptureFile {
 public:
  CaptureFile() = default;
  ~CaptureFile();
  CaptureFile(const CaptureFile&) = delete;
  CaptureFile& operator=(const CaptureFile&) = delete;

  // Opens a capture; false with error() set to a one-line reason when it cannot be read.
  bool open(const std::string& path);

  enum class Next { Packet, End, Truncated };
  // The next record; Truncated when the file ends inside a record (error() says where).
  Next next(CapturedPacket& packet);

  int link_type() const { return link_type_; }
  std::string link_type_name() const;  // "EN10MB (Ethernet)", "USER0"
  const std::string& error() const { return error_; }
  std::uint64_t packets() const { return packets_; }
  std::uint64_t size() const { return size_; }
  std::uint64_t position() const;  // bytes of the file read so far

 private:
  std::FILE* file_ = nullptr;
  pcap_t* pcap_ = nullptr;
  int link_type_ = -1;
  std::string error_;
  std::uint64_t packets_ = 0;
  std::uint64_t size_ = 0;
};

// The largest record among the first `records` of a capture (0 when it cannot be read).
std::size_t largest_early_record(const std::string& path, std::size_t records);

}  // namespace pvtap
