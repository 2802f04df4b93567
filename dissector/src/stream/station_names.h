// StationNames: what each station of a bus said of itself so far, in bus order.
#pragma once

#include <array>
#include <cstdint>

#include "pvtap/session/bus_report.h"
#include "pvtap/session/bus_session.h"

namespace pvtap::dissector {

// Fed every frame on the first pass, as pvtap audit's station table learns a device's name
// (a good device identification or report server ID reply). The name a frame shows is the
// one known when the session decided it, so a first pass and a later pass show the same.
class StationNames {
 public:
  // Learns from `f` and returns the name of its station as known after it (null: none yet).
  // The text lives in wmem file scope.
  const char* note(const SessionFrame& f);

 private:
  std::array<DeviceName, 256> said_;
  std::array<const char*, 256> text_{};
};

}  // namespace pvtap::dissector
