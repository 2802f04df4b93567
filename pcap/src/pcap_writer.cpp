#include "pvtap/pcap/pcap_writer.h"

#include <pcap/pcap.h>

namespace pvtap {

PcapWriter::~PcapWriter() {
  close();
}

bool PcapWriter::open(const std::string& path, int link_type, int snap_length) {
  pcap_ = pcap_open_dead(link_type, snap_length);
  if (pcap_ == nullptr) {
    error_ = "cannot set up a pcap writer";
    return false;
  }
  dumper_ = pcap_dump_open(pcap_, path.c_str());
  if (dumper_ == nullptr) {
    error_ = pcap_geterr(pcap_);
    pcap_close(pcap_);
    pcap_ = nullptr;
    return false;
  }
  return true;
}

void PcapWriter::write(std::int64_t micros, std::span<const std::uint8_t> record,
                       std::uint32_t length_on_wire) {
  if (dumper_ == nullptr) return;
  pcap_pkthdr header{};
  header.ts.tv_sec = static_cast<time_t>(micros / 1'000'000);
  header.ts.tv_usec = static_cast<suseconds_t>(micros % 1'000'000);
  header.caplen = static_cast<bpf_u_int32>(record.size());
  header.len = length_on_wire != 0 ? length_on_wire : header.caplen;
  pcap_dump(reinterpret_cast<u_char*>(dumper_), &header, record.data());
}

bool PcapWriter::flush() {
  if (dumper_ == nullptr) return true;
  if (pcap_dump_flush(dumper_) == 0) return true;
  error_ = "cannot write the file (disk full?)";
  return false;
}

bool PcapWriter::close() {
  bool ok = true;
  if (dumper_ != nullptr) {
    ok = pcap_dump_flush(dumper_) == 0;
    if (!ok) error_ = "cannot write the file (disk full?)";
    pcap_dump_close(dumper_);
    dumper_ = nullptr;
  }
  if (pcap_ != nullptr) {
    pcap_close(pcap_);
    pcap_ = nullptr;
  }
  return ok;
}

}  // namespace pvtap
