// LiveCapture: reading a capture that is set up, without blocking.
#include "sources/live_capture.h"

#include <pcap/pcap.h>

namespace pvtap::analyzer {

bool LiveCapture::open(const LiveCaptureSettings& settings) {
  if (!set_up_live_capture(settings, pcap_, setup_, error_)) return false;
  char errbuf[PCAP_ERRBUF_SIZE] = {};
  if (pcap_setnonblock(pcap_.get(), 1, errbuf) != 0) {
    error_ = std::string("cannot read without blocking: ") + errbuf;
    return false;
  }
  fd_ = pcap_get_selectable_fd(pcap_.get());
  return true;
}

int LiveCapture::dispatch(int limit, const PacketHandler& handler) {
  handler_ = &handler;
  const int rc = pcap_dispatch(pcap_.get(), limit, &LiveCapture::on_packet,
                               reinterpret_cast<unsigned char*>(this));
  handler_ = nullptr;
  if (rc == PCAP_ERROR_BREAK) return 0;
  if (rc < 0) {
    error_ = pcap_geterr(pcap_.get());
    return -1;
  }
  return rc;
}

void LiveCapture::on_packet(unsigned char* user, const pcap_pkthdr* header,
                            const unsigned char* data) {
  auto& self = *reinterpret_cast<LiveCapture*>(user);
  ++self.packets_;
  (*self.handler_)(packet_of(*header, data, self.setup_.nanoseconds));
}

LiveDrops LiveCapture::drops() const {
  pcap_stat stats{};
  if (!pcap_ || pcap_stats(pcap_.get(), &stats) != 0) return {};
  return LiveDrops{stats.ps_drop, stats.ps_ifdrop};
}

}  // namespace pvtap::analyzer
