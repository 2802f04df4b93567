// LiveCapture: a libpcap capture on a network interface, read without blocking.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "pvtap/capture/capture_file.h"

struct pcap_pkthdr;

namespace pvtap::analyzer {

// LiveCaptureSettings: which interface, and which of its traffic (gateway ports, BPF filter).
struct LiveCaptureSettings {
  std::string interface;
  std::vector<std::uint16_t> ports;  // each is matched as TCP and UDP, either side
  std::string filter;                // the user's BPF filter, AND-ed with the ports
};

// The BPF filter for `ports` and a user filter: "(tcp port 1 or udp port 1 ...) and (user)";
// empty when there is neither.
std::string live_capture_filter(const std::vector<std::uint16_t>& ports,
                                const std::string& user_filter);

// LiveDrops: libpcap's drop counters at the end; nullopt where the platform has none.
struct LiveDrops {
  std::optional<std::uint64_t> kernel;
  std::optional<std::uint64_t> interface;
};

class LiveCapture {
 public:
  LiveCapture() = default;
  ~LiveCapture();
  LiveCapture(const LiveCapture&) = delete;
  LiveCapture& operator=(const LiveCapture&) = delete;

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

  int link_type() const { return link_type_; }
  std::string link_type_name() const;  // "EN10MB (Ethernet)"
  const std::string& filter() const { return filter_; }
  const std::string& error() const { return error_; }
  // Warnings libpcap gave when it activated the capture, each a line.
  const std::vector<std::string>& warnings() const { return warnings_; }
  std::uint64_t packets() const { return packets_; }
  LiveDrops drops() const;

 private:
  bool activate(const std::string& interface);
  bool apply_filter(const std::string& text);
  bool check_link_type();
  static void on_packet(unsigned char* user, const pcap_pkthdr* header, const unsigned char* data);

  pcap_t* pcap_ = nullptr;
  int fd_ = -1;
  int link_type_ = -1;
  bool nanoseconds_ = false;  // timestamps in nanoseconds, else microseconds
  std::string filter_;
  std::string error_;
  std::vector<std::string> warnings_;
  std::uint64_t packets_ = 0;
  const PacketHandler* handler_ = nullptr;  // during dispatch()
};

}  // namespace pvtap::analyzer
