// BusProvider: where a flow found to be a gateway's gets its bus. The run that owns the buses
// implements it, so that the gateway layer needs nothing above it.
#pragma once

#include <string>

#include "pvtap/session/bus_session.h"

namespace pvtap::analyzer {

class BusProvider {
 public:
  // The bus behind the gateway endpoint `name`, made on first use; the same bus for every
  // later connection to that endpoint, so that reconnections continue it.
  virtual BusSession& gateway_bus(const std::string& name) = 0;
  // The bus behind a Solarman V5 logger stick, named `v5:SERIAL`, likewise made on first use:
  // its frames arrive whole, one per V5 frame, timed at the LAN side.
  virtual BusSession& logger_bus(const std::string& name) = 0;

 protected:
  ~BusProvider() = default;
};

}  // namespace pvtap::analyzer
