#include <pcap/pcap.h>

#include "outputs/bus_bytes.h"
#include "outputs/capture_outputs.h"
#include "pvtap/capture/pcap_writer.h"

namespace pvtap::sim {
namespace {

// An FTDI adapter hands bytes over when its 16 ms latency timer runs out or its 62-byte
// packet is full, whichever comes first.
constexpr Micros kLatencyTimer = 16'000;
constexpr std::size_t kPacketBytes = 62;

}  // namespace

std::string write_chunked_capture(const BusTimeline& timeline, const std::string& path) {
  PcapWriter file;
  if (!file.open(path, DLT_USER0)) return file.error();
  const std::vector<TimedByte> bytes = bus_bytes(timeline);
  std::vector<std::uint8_t> chunk;
  Micros deadline = 0;
  Micros last = 0;
  for (const TimedByte& b : bytes) {
    if (!chunk.empty() && b.time > deadline) {
      file.write(deadline, chunk);
      chunk.clear();
    }
    if (chunk.empty()) deadline = b.time + kLatencyTimer;
    chunk.push_back(b.value);
    last = b.time;
    if (chunk.size() == kPacketBytes) {
      file.write(last, chunk);
      chunk.clear();
    }
  }
  if (!chunk.empty()) file.write(deadline, chunk);
  return file.close() ? std::string{} : file.error();
}

}  // namespace pvtap::sim
