#include "command/lan_options.h"

#include <algorithm>

namespace pvtap::sim {
namespace {

// Bus faults a LAN client can see through a stick or gateway. Noise, duplicates and damaged
// requests happen between the stick and the device: what the stick would make of them is not
// known, so they are not simulated. A gateway checks CRCs and keeps damaged replies to itself.
bool carried(FaultKind kind, bool v5) {
  switch (kind) {
    case FaultKind::Missing:
    case FaultKind::Slow:
    case FaultKind::ErrorReply:
    case FaultKind::CountMismatch:
      return true;
    case FaultKind::Corrupt:
      return v5;  // a stick wraps whatever the bus gave it
    default:
      return false;
  }
}

std::string fault_problem(const FaultPlan& plan, bool v5) {
  for (unsigned k = 0; k < kFaultKinds; ++k) {
    const auto kind = static_cast<FaultKind>(k);
    if (plan[kind] > 0 && !carried(kind, v5))
      return std::string(v5 ? "--v5" : "--mbap") + " does not carry the bus fault " +
             std::string(to_string(kind));
  }
  return {};
}

}  // namespace

void add_lan_options(CLI::App& app, LanOutputs& lan) {
  auto* v5 = app.add_option("--v5", lan.v5,
                            "write the Solarman V5 capture of a client reading the bus through a "
                            "logger stick on TCP 8899");
  auto* mbap = app.add_option("--mbap", lan.mbap,
                              "write the Modbus/TCP capture of a client reading the bus through a "
                              "gateway on TCP 502");
  v5->excludes(mbap);
  app.add_option("--v5-faults", lan.v5_faults,
                 "none or kind=percent,... (quirk drop bad_checksum split merge stick_code "
                 "wrong_serial late beat_first)");
  app.add_option("--heartbeat", lan.v5_options.heartbeat_s,
                 "--v5: seconds between the stick's heartbeats (0: none)");
  app.add_option("--data-report", lan.v5_options.data_report_s,
                 "--v5: seconds between the stick's data reports (0: none)");
  app.add_option("--mbap-faults", lan.mbap_faults,
                 "none or kind=percent,... (pipeline lying_length)");
}

std::string finish_lan_options(LanOutputs& lan, const SimConfig& config, bool bus_outputs) {
  std::string error;
  const auto v5 = parse_carrier_faults(lan.v5_faults, v5_fault_kinds(), error);
  if (!v5) return error;
  const auto mbap = parse_carrier_faults(lan.mbap_faults, mbap_fault_kinds(), error);
  if (!mbap) return error;
  lan.v5_options.faults = *v5;
  lan.mbap_options.faults = *mbap;
  lan.mbap_options.bus_timeout_s = config.timeout_s;
  lan.v5_options.client_timeout_s = config.timeout_s;
  if (lan.v5.empty() && lan.mbap.empty()) return {};
  // The ground truth of such a run is the LAN's view (a reply the stick dropped is gone).
  if (bus_outputs) return "--v5 and --mbap are written alone (with --truth)";
  if (!std::all_of(config.dialects.begin(), config.dialects.end(), rtu_framed))
    return "--v5 and --mbap carry RTU frames: no ascii dialect";
  return fault_problem(config.faults, !lan.v5.empty());
}

}  // namespace pvtap::sim
