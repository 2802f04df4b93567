// FlowStreams: the two byte streams of one TCP or UDP flow between a master and a gateway,
// and whether the connection has ended.
#pragma once

#include <cstdint>
#include <optional>
#include <span>

#include "pvtap/carriers/tcp_stream.h"
#include "pvtap/framing/bus_chunk.h"
#include "pvtap/pcap/network_packet.h"
#include "report/network_stats.h"

namespace pvtap::analyzer {

// FlowBytes: where a flow's bytes go, in order per direction, with the stretches lost.
class FlowBytes {
 public:
  virtual void data(Direction d, std::span<const std::uint8_t> bytes, double time) = 0;
  virtual void gap(Direction d, std::uint64_t lost, double time) = 0;

 protected:
  ~FlowBytes() = default;
};

// TCP segments are put in order per direction (TcpDirectionStream); UDP datagrams go out as
// they come, each its own piece.
class FlowStreams {
 public:
  // `slave` is the gateway's side: a segment from it goes FromSlave.
  FlowStreams(Transport transport, const Endpoint& slave, double hole_wait, FlowBytes& bytes);

  Transport transport() const { return transport_; }
  const Endpoint& slave() const { return slave_; }
  const TcpDirectionStream& stream(Direction d) const {
    return d == Direction::ToSlave ? to_slave_.stream : from_slave_.stream;
  }

  void on_segment(const Segment& s, double time);
  // Gives up holes that waited longer than allowed.
  void expire(double now);
  // The earlier hole deadline of the two directions (TcpDirectionStream::hole_deadline).
  std::optional<double> hole_deadline() const;
  // End of the flow: every hole is lost, every byte delivered.
  void flush(double time);

  // No byte of the side opposite `d` is still missing. While one is (a hole waiting for a
  // retransmission), that side's turn is not over.
  bool other_complete(Direction d) const {
    const TcpDirectionStream& opposite =
        d == Direction::ToSlave ? from_slave_.stream : to_slave_.stream;
    return transport_ == Transport::Udp || !opposite.has_hole();
  }
  // FIN both ways or RST, and no hole left: nothing more will come.
  bool ended() const {
    const bool closed = reset_ || (to_slave_.fin && from_slave_.fin);
    return transport_ == Transport::Tcp && closed && !to_slave_.stream.has_hole() &&
           !from_slave_.stream.has_hole();
  }
  // What reassembly repaired; what it lost only for a flow whose bytes were analyzed.
  void add_stats(NetworkStats& into, bool analyzed) const;

 private:
  // Side: one direction's stream and the sink it delivers to, and whether its side sent FIN.
  struct Side : TcpStreamSink {
    Side(FlowBytes& to, Direction d, double hole_wait);
    Side(const Side&) = delete;
    Side& operator=(const Side&) = delete;
    void on_stream_data(std::span<const std::uint8_t> bytes, double time) override {
      target.data(direction, bytes, time);
    }
    void on_stream_gap(std::uint64_t lost, double time) override {
      target.gap(direction, lost, time);
    }
    FlowBytes& target;
    Direction direction;
    TcpDirectionStream stream;
    bool fin = false;
  };
  Side& side(Direction d) { return d == Direction::ToSlave ? to_slave_ : from_slave_; }

  Transport transport_;
  Endpoint slave_;
  Side to_slave_;
  Side from_slave_;
  bool reset_ = false;
};

}  // namespace pvtap::analyzer
