#include "pvtap/pcap/capture_file.h"

#include "pvtap/pcap/file_format.h"

#include <pcap/pcap.h>
#include <stdio_ext.h>
#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "pvtap/pcap/link_types.h"

namespace pvtap {
namespace {

constexpr std::size_t kReadBuffer = 1 << 20;

static_assert(dlt::kNull == DLT_NULL && dlt::kEthernet == DLT_EN10MB && dlt::kRaw == DLT_RAW &&
              dlt::kLoop == DLT_LOOP && dlt::kLinuxSll == DLT_LINUX_SLL &&
              dlt::kLinuxSll2 == DLT_LINUX_SLL2 && dlt::kUser0 == DLT_USER0 &&
              dlt::kUser15 == DLT_USER15 && dlt::kIpv4 == DLT_IPV4 && dlt::kIpv6 == DLT_IPV6 &&
              dlt::kRtacSerial == DLT_RTAC_SERIAL && dlt::kUpperPdu == DLT_WIRESHARK_UPPER_PDU);

// libpcap's reason for refusing a file, in the words a user needs: for a file of another
// format, what its first bytes look like.
std::string open_failure(const char* pcap_reason, const std::string& path) {
  const std::string reason = pcap_reason;
  if (reason.find("unknown file format") != std::string::npos) {
    std::string what = "not a pcap or pcapng capture (it begins " + first_bytes_text(path);
    if (file_format_of(path) == FileFormat::Zip) what += ": a zip, as a sigrok session is";
    return what + ")";
  }
  if (reason.find("truncated") != std::string::npos) {
    return "not a capture: the file is empty or ends inside its header (" + reason + ")";
  }
  return reason;
}

// libpcap's reason for stopping inside the records: a file cut short, or a record that cannot
// be true (a length beyond any capture's), said as such with where reading stopped.
std::string damage_text(const std::string& reason, std::uint64_t at) {
  const std::string where = " at byte " + std::to_string(at);
  if (reason.find("truncated") != std::string::npos) {
    return "truncated: the file ends inside a record" + where + " (" + reason + ")";
  }
  return "corrupt" + where + ": " + reason;
}

}  // namespace

CapturedPacket packet_of(const pcap_pkthdr& header, const unsigned char* data, bool nanoseconds) {
  CapturedPacket packet;
  const double fraction = nanoseconds ? 1e-9 : 1e-6;
  packet.time =
      static_cast<double>(header.ts.tv_sec) + static_cast<double>(header.ts.tv_usec) * fraction;
  packet.bytes = std::span<const std::uint8_t>(data, header.caplen);
  packet.length_on_wire = header.len;
  return packet;
}

CaptureFile::~CaptureFile() {
  if (pcap_ != nullptr) {
    pcap_close(pcap_);  // closes file_ too
  } else if (file_ != nullptr) {
    std::fclose(file_);
  }
}

bool CaptureFile::open(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    error_ = std::strerror(errno);
    return false;
  }
  if (S_ISDIR(st.st_mode)) {
    error_ = "is a directory";
    return false;
  }
  size_ = static_cast<std::uint64_t>(st.st_size);
  file_ = std::fopen(path.c_str(), "rb");
  if (file_ == nullptr) {
    error_ = std::strerror(errno);
    return false;
  }
  // libpcap reads each record with two fread calls: a large buffer and no stream locking
  // (only this thread reads the file) keep that cheap. A small file needs no more buffer than
  // its size (an audit of many small files, or a fuzz target opening one per input, would
  // map and clear a mebibyte each time).
  const std::size_t buffer =
      S_ISREG(st.st_mode) ? std::clamp<std::size_t>(size_, BUFSIZ, kReadBuffer) : kReadBuffer;
  std::setvbuf(file_, nullptr, _IOFBF, buffer);
  __fsetlocking(file_, FSETLOCKING_BYCALLER);
  char errbuf[PCAP_ERRBUF_SIZE] = {};
  pcap_ = pcap_fopen_offline_with_tstamp_precision(file_, PCAP_TSTAMP_PRECISION_NANO, errbuf);
  if (pcap_ == nullptr) {
    error_ = open_failure(errbuf, path);
    return false;
  }
  link_type_ = pcap_datalink(pcap_);
  return true;
}

CaptureFile::Next CaptureFile::next(CapturedPacket& packet) {
  pcap_pkthdr* header = nullptr;
  const u_char* data = nullptr;
  const int rc = pcap_next_ex(pcap_, &header, &data);
  if (rc == 1) {
    ++packets_;
    packet = packet_of(*header, data, true);  // opened with nanosecond precision
    return Next::Packet;
  }
  if (rc == PCAP_ERROR_BREAK) return Next::End;
  error_ = damage_text(pcap_geterr(pcap_), position());
  return Next::Truncated;
}

std::string CaptureFile::link_type_name() const {
  return pvtap::link_type_name(link_type_);
}

std::uint64_t CaptureFile::position() const {
  if (pcap_ == nullptr) return 0;
  const off_t at = ftello(pcap_file(pcap_));
  return at < 0 ? 0 : static_cast<std::uint64_t>(at);
}

std::size_t largest_early_record(const std::string& path, std::size_t records) {
  CaptureFile file;
  if (!file.open(path)) return 0;
  std::size_t largest = 0;
  CapturedPacket packet;
  while (file.packets() < records && file.next(packet) == CaptureFile::Next::Packet) {
    largest = std::max(largest, packet.bytes.size());
  }
  return largest;
}

}  // namespace pvtap
