#include <pcap/pcap.h>

#include "outputs/bus_bytes.h"
#include "outputs/capture_outputs.h"
#include "pvtap/pcap/pcap_writer.h"
#include "sim_random.h"

namespace pvtap::sim {
namespace {

// An FTDI adapter hands bytes over when its 16 ms latency timer runs out or its 62-byte
// packet is full, whichever comes first.
constexpr Micros kLatencyTimer = 16'000;
constexpr std::size_t kPacketBytes = 62;

// UsbTransfer: bytes the adapter handed over at once, and when.
struct UsbTransfer {
  Micros time = 0;
  std::vector<std::uint8_t> bytes;
};

std::vector<UsbTransfer> usb_transfers(const BusTimeline& timeline, std::optional<Role> pair) {
  std::vector<UsbTransfer> out;
  UsbTransfer pending;
  Micros deadline = 0;
  for (const TimedByte& b : bus_bytes(timeline)) {
    if (pair && b.side != *pair) continue;
    if (!pending.bytes.empty() && b.time > deadline) {
      pending.time = deadline;
      out.push_back(std::move(pending));
      pending = {};
    }
    if (pending.bytes.empty()) deadline = b.time + kLatencyTimer;
    pending.bytes.push_back(b.value);
    if (pending.bytes.size() == kPacketBytes) {
      pending.time = b.time;
      out.push_back(std::move(pending));
      pending = {};
    }
  }
  if (!pending.bytes.empty()) {
    pending.time = deadline;
    out.push_back(std::move(pending));
  }
  return out;
}

// The capturing program gets to read each transfer 0..max_delay late, as the OS schedules it,
// and a late read returns, as one record stamped when it returns, every transfer that had
// arrived by then.
std::vector<UsbTransfer> late_reads(std::vector<UsbTransfer> transfers, Micros max_delay,
                                    SimRandom& random) {
  std::vector<UsbTransfer> reads;
  for (UsbTransfer& t : transfers) {
    if (!reads.empty() && t.time <= reads.back().time) {
      reads.back().bytes.insert(reads.back().bytes.end(), t.bytes.begin(), t.bytes.end());
      continue;
    }
    t.time += random.between(0, max_delay);
    reads.push_back(std::move(t));
  }
  return reads;
}

}  // namespace

std::string write_chunked_capture(const BusTimeline& timeline, const std::string& path,
                                  const ChunkedReads& reads, std::optional<Role> pair) {
  PcapWriter file;
  if (!file.open(path, DLT_USER0)) return file.error();
  std::vector<UsbTransfer> records = usb_transfers(timeline, pair);
  if (reads.max_delay_ms > 0) {
    // Each pair's adapter is read late by chance of its own.
    const std::uint64_t stream = pair ? static_cast<std::uint64_t>(*pair) + 1 : 0;
    SimRandom random((reads.seed ^ 0x5E1A7EDull) + stream);
    records = late_reads(std::move(records), Micros{reads.max_delay_ms} * 1000, random);
  }
  for (const UsbTransfer& r : records) file.write(r.time, r.bytes);
  return file.close() ? std::string{} : file.error();
}

}  // namespace pvtap::sim
