#include "pvtap/pcap/rtac_record.h"

namespace pvtap {
namespace {

constexpr std::size_t kRtacHeader = 12;
constexpr std::uint8_t kRtacCaptureDataLost = 0x05;

}  // namespace

std::optional<SerialRecord> rtac_serial_record(std::span<const std::uint8_t> record) {
  if (record.size() < kRtacHeader) return std::nullopt;
  SerialRecord r;
  r.bytes = record.subspan(kRtacHeader);
  r.data_lost_before = record[8] == kRtacCaptureDataLost;
  return r;
}

}  // namespace pvtap
