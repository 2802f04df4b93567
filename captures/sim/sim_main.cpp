// pvtap-sim: simulates a master polling inverters and writes the bus as captures.
#include <iostream>
#include <optional>

#include "bus/bus_master.h"
#include "command/sim_command.h"
#include "lan/mbap_session.h"
#include "lan/v5_session.h"
#include "logic/logic_truth.h"
#include "logic/srzip_writer.h"
#include "outputs/capture_outputs.h"
#include "outputs/ground_truth.h"
#include "outputs/serial_pacer.h"

namespace {

// Runs one writer when its output was asked for; false (with a message) when it failed.
template <typename Write>
bool produce(const std::string& path, Write write) {
  if (path.empty()) return true;
  const std::string error = write();
  if (error.empty()) return true;
  std::cerr << "pvtap-sim: " << path << ": " << error << "\n";
  return false;
}

// The LAN carrier asked for, planned; it makes the timeline what the LAN client saw.
std::optional<pvtap::sim::LanCapture> plan_lan(pvtap::sim::BusTimeline& timeline,
                                               const pvtap::sim::SimCommand& cmd) {
  using namespace pvtap::sim;
  const LanOutputs& lan = cmd.outputs.lan;
  if (!lan.v5.empty())
    return plan_v5_session(timeline, lan.v5_options, cmd.config.start, cmd.config.seed);
  if (!lan.mbap.empty()) return plan_mbap_session(timeline, lan.mbap_options, cmd.config.seed);
  return std::nullopt;
}

// --sr: the bus laid out at the session's format, with its drivers, glitches and violations;
// the timeline moves to the times the session shows. The truth describes it.
std::optional<pvtap::sim::LanTruth> plan_logic(pvtap::sim::BusTimeline& timeline,
                                               const pvtap::sim::SimCommand& cmd,
                                               pvtap::sim::LogicSignals& signals) {
  using namespace pvtap::sim;
  const LogicOptions& o = cmd.outputs.logic;
  if (o.path.empty()) return std::nullopt;
  const LogicLayout layout = lay_out_logic(timeline, o, cmd.config.baud, cmd.config.seed);
  signals = logic_signals(layout, o, cmd.config.seed);
  return logic_truth(layout, signals, o, cmd.config.baud);
}

}  // namespace

int main(int argc, char** argv) {
  using namespace pvtap::sim;
  int exit_code = 0;
  const auto cmd = parse_sim_command(argc, argv, exit_code);
  if (!cmd) return exit_code;
  BusTimeline timeline = BusMaster(cmd->config).run();
  const SimOutputs& out = cmd->outputs;
  const auto lan = plan_lan(timeline, *cmd);
  LogicSignals signals;
  const auto logic = plan_logic(timeline, *cmd, signals);
  const LanTruth* carrier_truth = lan ? &lan->truth : logic ? &*logic : nullptr;
  const std::string& lan_path = out.lan.v5.empty() ? out.lan.mbap : out.lan.v5;
  bool ok =
      produce(lan_path, [&] { return write_tcp_session(lan->segments, lan->ends, lan_path); });
  ok = produce(out.logic.path, [&] { return write_srzip(signals, out.logic.path); }) && ok;
  ok = produce(out.pdu, [&] { return write_pdu_capture(timeline, out.pdu); }) && ok;
  ok = produce(out.gateway,
               [&] { return write_gateway_capture(timeline, out.gateway, cmd->config.seed); }) &&
       ok;
  const ChunkedReads reads{cmd->config.seed, out.read_delay_ms};
  ok = produce(out.chunked, [&] { return write_chunked_capture(timeline, out.chunked, reads); }) &&
       ok;
  // --duplex REQ REP: one capture per pair, the requests' first.
  for (std::size_t i = 0; i < out.duplex.size(); ++i) {
    const pvtap::Role pair = i == 0 ? pvtap::Role::Request : pvtap::Role::Response;
    ok = produce(out.duplex[i],
                 [&] { return write_chunked_capture(timeline, out.duplex[i], reads, pair); }) &&
         ok;
  }
  ok = produce(
           out.truth,
           [&] { return write_ground_truth(timeline, cmd->config, out.truth, carrier_truth); }) &&
       ok;
  ok = produce(out.device,
               [&] { return pace_onto_device(timeline, out.device, cmd->config.baud); }) &&
       ok;
  if (out.duplex_devices.size() == 2) {
    ok =
        produce(out.duplex_devices[0],
                [&] { return pace_onto_duplex(timeline, out.duplex_devices, cmd->config.baud); }) &&
        ok;
  }
  return ok ? 0 : 1;
}
