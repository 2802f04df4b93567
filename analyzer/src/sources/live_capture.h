// LiveCapture: a libpcap capture on a network interface, read without blocking.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "pvtap/pcap/capture_file.h"
#include "sources/live_capture_setup.h"

struct pcap_pkthdr;

namespace pvtap::analyzer {

// LiveDrops: libpcap's drop counters at the end; nullopt where the platform has none.
struct LiveDrops {
  std::optional<std::uint64_t> kernel;
  std::optional<std::uint64_t> interface;
};

class LiveCapture {
 public:
  // Opens and activates the capture, with its filter set; false with error() set to a
  // one-line reason (a missing capability, an unknown interface, a bad filter).
  bool open(const LiveCaptureSettings& settings);

  // The file descriptor to wait on for packets; -1 when the platform has none (then poll
  // dispatch() on a timer).
  int selectable_fd() const { return fd_; }

  using PacketHandler = std::function<void(const CapturedPacket&)>;
  // Hands the packets waiting (at most `limit`) to `handler`, without blocking; the number
  // handed, or -1 with error() set when the capture failed (e.g. the interface went away).
  int dispatch(int limit, const PacketHandler& handler);

  // The link type, the filter and libpcap's warnings, once open.
  const LiveCaptureSetup& setup() const { return setup_; }
  const std::string& error() const { return error_; }
  std::uint64_t packets() const { return packets_; }
  LiveDrops drops() const;

 private:
  static void on_packet(unsigned char* user, const pcap_pkthdr* header, const unsigned char* data);

  PcapHandle pcap_;
  int fd_ = -1;
  LiveCaptureSetup setup_;
  std::string error_;
  std::uint64_t packets_ = 0;
  const PacketHandler* handler_ = nullptr;  // during dispatch()
};

}  // namespace pvtap::analyzer
