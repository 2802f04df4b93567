// Renders a bus plan as a serial-to-TCP (or UDP) gateway's traffic: the master's requests go
// to the gateway, the inverters' replies come back, cut into segments by the gateway's timer.
#pragma once

#include <cstdint>
#include <vector>

#include "bus_plan.h"
#include "pvtap/pcap/capture_writer.h"
#include "pvtap/pcap/packet_builder.h"

namespace pvtap::forge {

// GatewaySegment: a piece of one direction's byte stream, captured at `time`.
struct GatewaySegment {
  Direction direction = Direction::ToSlave;
  std::uint64_t begin = 0;  // stream offsets
  std::uint64_t end = 0;
  double time = 0;
  bool lost = false;  // sent, acknowledged, but missing from the capture
};

// GatewayLayout: the two hosts and how the flow looks on the wire.
struct GatewayLayout {
  LinkLayer link = LinkLayer::Ethernet;
  Endpoint master = ipv4_endpoint(10, 0, 0, 1, 50123);
  Endpoint gateway = ipv4_endpoint(10, 0, 0, 2, 4001);
  bool udp = false;
  bool handshake = true;
  bool acks = true;  // the receiver acknowledges every data segment 0.3 ms later
  std::uint32_t master_isn = 1000000;
  std::uint32_t gateway_isn = 0xFFFFFF00;  // wraps around zero within the first few hundred bytes
};

class GatewayRender {
 public:
  // One segment per transmission, captured 0.2 ms after its last byte.
  GatewayRender(const BusPlan& plan, GatewayLayout layout);

  std::vector<GatewaySegment>& segments() { return segments_; }
  // Edits that make reassembly work; indexes refer to segments() at the time of the call.
  void split(std::size_t i, std::uint64_t first_part_bytes, double second_delay = 0.002);
  void merge_with_next(std::size_t i);  // the next segment of the same direction
  void swap_with_next(std::size_t i);   // captured in the opposite order
  void retransmit(std::size_t i, double delay, std::uint64_t extra_before = 0);
  // The segment also carries the `bytes` before it again (a repacketized retransmission).
  void overlap_previous(std::size_t i, std::uint64_t bytes) { segments_[i].begin -= bytes; }
  // The segment that starts with plan item `item`.
  std::size_t segment_of(std::size_t item) const;
  void lose(std::size_t i);

  // Writes the packets (handshake, segments, acknowledgements, FINs); returns the audit the
  // capture must give.
  Expected write(CaptureWriter& out) const;

 private:
  struct Wire;
  void write_segment(const GatewaySegment& seg, Wire& w, CaptureWriter& out) const;

  const BusPlan& plan_;
  GatewayLayout layout_;
  std::vector<GatewaySegment> segments_;
  Bytes to_slave_;
  Bytes from_slave_;
};

}  // namespace pvtap::forge
