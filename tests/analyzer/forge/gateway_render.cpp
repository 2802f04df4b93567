#include "gateway_render.h"

#include <algorithm>
#include <map>

namespace pvtap::forge {
namespace {

constexpr double kCaptureDelay = 0.0002;  // from the last byte on the bus to the capture
constexpr double kAckDelay = 0.0003;

// Received: which stream bytes a receiver has, to compute its cumulative acknowledgement.
class Received {
 public:
  void add(std::uint64_t begin, std::uint64_t end) {
    ranges_[begin] = std::max(ranges_[begin], end);
    auto it = ranges_.begin();
    while (it != ranges_.end() && it->first <= contiguous_) {
      contiguous_ = std::max(contiguous_, it->second);
      it = ranges_.erase(it);
    }
  }
  std::uint64_t contiguous() const { return contiguous_; }

 private:
  std::map<std::uint64_t, std::uint64_t> ranges_;
  std::uint64_t contiguous_ = 0;
};

}  // namespace

GatewayRender::GatewayRender(const BusPlan& plan, GatewayLayout layout)
    : plan_(plan), layout_(layout) {
  const std::vector<std::uint64_t> offsets = plan.stream_offsets(true);
  std::vector<std::size_t> order(plan.items().size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return plan.items()[a].start < plan.items()[b].start;
  });
  for (const std::size_t i : order) {
    const BusItem& item = plan.items()[i];
    Bytes& stream = item.direction == Direction::ToSlave ? to_slave_ : from_slave_;
    stream.insert(stream.end(), item.bytes.begin(), item.bytes.end());
    segments_.push_back(GatewaySegment{item.direction, offsets[i], offsets[i] + item.bytes.size(),
                                       item.end + kCaptureDelay, false});
  }
}

void GatewayRender::split(std::size_t i, std::uint64_t first_part_bytes, double second_delay) {
  GatewaySegment second = segments_[i];
  segments_[i].end = segments_[i].begin + first_part_bytes;
  second.begin = segments_[i].end;
  second.time += second_delay;
  segments_[i].time -= plan_.char_time() * static_cast<double>(second.end - second.begin);
  segments_.insert(segments_.begin() + static_cast<std::ptrdiff_t>(i) + 1, second);
}

void GatewayRender::merge_with_next(std::size_t i) {
  for (std::size_t j = i + 1; j < segments_.size(); ++j) {
    if (segments_[j].direction != segments_[i].direction) continue;
    segments_[i].end = segments_[j].end;
    segments_[i].time = segments_[j].time;
    segments_.erase(segments_.begin() + static_cast<std::ptrdiff_t>(j));
    // Whatever the other direction sent in between is now captured after the merged segment.
    std::stable_sort(
        segments_.begin(), segments_.end(),
        [](const GatewaySegment& a, const GatewaySegment& b) { return a.time < b.time; });
    return;
  }
}

void GatewayRender::swap_with_next(std::size_t i) {
  std::swap(segments_[i], segments_[i + 1]);
  std::swap(segments_[i].time, segments_[i + 1].time);
}

void GatewayRender::retransmit(std::size_t i, double delay, std::uint64_t extra_before) {
  GatewaySegment copy = segments_[i];
  copy.begin -= std::min(copy.begin, extra_before);
  copy.time += delay;
  copy.lost = false;
  auto at = std::upper_bound(segments_.begin(), segments_.end(), copy.time,
                             [](double t, const GatewaySegment& s) { return t < s.time; });
  segments_.insert(at, copy);
}

std::size_t GatewayRender::segment_of(std::size_t item) const {
  const std::uint64_t begin = plan_.stream_offsets(true)[item];
  const Direction d = plan_.items()[item].direction;
  for (std::size_t i = 0; i < segments_.size(); ++i) {
    if (segments_[i].direction == d && segments_[i].begin == begin) return i;
  }
  return segments_.size();
}

void GatewayRender::lose(std::size_t i) {
  segments_[i].lost = true;
}

// Wire: the TCP state of both ends while the segments are written.
struct GatewayRender::Wire {
  Wire(const GatewayLayout& g) : mseq(g.master_isn + 1), sseq(g.gateway_isn + 1) {}
  std::uint32_t ack_to(bool to_slave) const {  // the receiver's cumulative acknowledgement
    return to_slave ? mseq + static_cast<std::uint32_t>(at_gateway.contiguous())
                    : sseq + static_cast<std::uint32_t>(at_master.contiguous());
  }
  std::uint32_t next_seq(bool of_master) const {
    return of_master ? mseq + static_cast<std::uint32_t>(master_sent)
                     : sseq + static_cast<std::uint32_t>(gateway_sent);
  }
  const std::uint32_t mseq;
  const std::uint32_t sseq;
  Received at_gateway;  // bytes of the master's stream the gateway has
  Received at_master;
  std::uint64_t master_sent = 0;
  std::uint64_t gateway_sent = 0;
};

void GatewayRender::write_segment(const GatewaySegment& seg, Wire& w, CaptureWriter& out) const {
  const GatewayLayout& g = layout_;
  const bool to_slave = seg.direction == Direction::ToSlave;
  const Bytes& stream = to_slave ? to_slave_ : from_slave_;
  const std::span<const std::uint8_t> payload(stream.data() + seg.begin, seg.end - seg.begin);
  const Endpoint& from = to_slave ? g.master : g.gateway;
  const Endpoint& to = to_slave ? g.gateway : g.master;
  const std::uint32_t seq = (to_slave ? w.mseq : w.sseq) + static_cast<std::uint32_t>(seg.begin);
  (to_slave ? w.at_gateway : w.at_master).add(seg.begin, seg.end);
  std::uint64_t& sent = to_slave ? w.master_sent : w.gateway_sent;
  sent = std::max(sent, seg.end);
  if (!seg.lost && g.udp) {
    out.write(seg.time, udp_packet(g.link, {from, to}, payload));
  } else if (!seg.lost) {
    out.write(seg.time,
              tcp_packet(g.link, {from, to},
                         {seq, w.ack_to(!to_slave), tcp_flag::kAck | tcp_flag::kPsh}, payload));
  }
  if (g.udp || !g.acks) return;
  // The receiver acknowledges what it holds, lost segments included: it did get them.
  out.write(seg.time + kAckDelay,
            tcp_packet(g.link, {to, from},
                       {w.next_seq(!to_slave), w.ack_to(to_slave), tcp_flag::kAck}, {}));
}

Expected GatewayRender::write(CaptureWriter& out) const {
  const GatewayLayout& g = layout_;
  const Endpoint& m = g.master;
  const Endpoint& s = g.gateway;
  Wire w(g);
  const bool tcp_frame = !g.udp && g.handshake;
  const double first = segments_.empty() ? 0.0 : segments_.front().time;
  if (tcp_frame) {
    out.write(first - 0.010, tcp_packet(g.link, {m, s}, {g.master_isn, 0, tcp_flag::kSyn}, {}));
    out.write(
        first - 0.009,
        tcp_packet(g.link, {s, m}, {g.gateway_isn, w.mseq, tcp_flag::kSyn | tcp_flag::kAck}, {}));
    out.write(first - 0.008, tcp_packet(g.link, {m, s}, {w.mseq, w.sseq, tcp_flag::kAck}, {}));
  }
  std::vector<BusPlan::LostRange> lost;
  double last = first;
  for (const GatewaySegment& seg : segments_) {
    write_segment(seg, w, out);
    last = std::max(last, seg.time);
    if (seg.lost) lost.push_back(BusPlan::LostRange{seg.direction, seg.begin, seg.end});
  }
  if (tcp_frame) {
    const std::uint32_t mfin = w.next_seq(true);
    const std::uint32_t sfin = w.next_seq(false);
    out.write(last + 1.5,
              tcp_packet(g.link, {m, s}, {mfin, sfin, tcp_flag::kFin | tcp_flag::kAck}, {}));
    out.write(last + 1.501,
              tcp_packet(g.link, {s, m}, {sfin, mfin + 1, tcp_flag::kFin | tcp_flag::kAck}, {}));
    out.write(last + 1.502, tcp_packet(g.link, {m, s}, {mfin + 1, sfin + 1, tcp_flag::kAck}, {}));
  }
  return plan_.expected(lost);
}

}  // namespace pvtap::forge
