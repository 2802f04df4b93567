// InterfaceSource: pvtap sniff --interface: libpcap hands over a gateway's packets as they
// cross, and they go down the pipeline as the records of a capture file do. The loop wakes
// when packets come or the pipeline's next deadline falls due, so that timeouts are judged
// while the capture runs and not only when the next packet comes.
#pragma once

#include <cstdint>
#include <vector>

#include "pipeline/pipeline.h"
#include "report/live_report.h"
#include "sources/live_capture.h"
#include "sources/live_loop.h"
#include "sources/live_options.h"

namespace pvtap::analyzer {

class InterfaceSource {
 public:
  // The interface of `live`, with a filter for the gateway `ports` (none: every port).
  InterfaceSource(const LiveOptions& live, const std::vector<std::uint16_t>& ports,
                  Pipeline& pipeline);

  // Opens the capture and says so on stderr; once the line is there every packet is seen
  // (scripts wait for it, as they do for tcpdump's "listening on"). False after saying why
  // it cannot be opened.
  bool open();
  // Captures until the loop says stop; libpcap's counters go into `live`.
  void run(LiveLoop& loop, LiveSources& live);

 private:
  const LiveOptions& live_;
  const std::vector<std::uint16_t>& ports_;
  Pipeline& pipeline_;
  LiveCapture capture_;
};

}  // namespace pvtap::analyzer
