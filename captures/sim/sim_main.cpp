// pvtap-sim: simulates a master polling inverters and writes the bus as captures.
#include <iostream>

#include "bus/bus_master.h"
#include "command/sim_command.h"
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

}  // namespace

int main(int argc, char** argv) {
  using namespace pvtap::sim;
  int exit_code = 0;
  const auto cmd = parse_sim_command(argc, argv, exit_code);
  if (!cmd) return exit_code;
  const BusTimeline timeline = BusMaster(cmd->config).run();
  const SimOutputs& out = cmd->outputs;
  bool ok = produce(out.pdu, [&] { return write_pdu_capture(timeline, out.pdu); });
  ok = produce(out.gateway,
               [&] { return write_gateway_capture(timeline, out.gateway, cmd->config.seed); }) &&
       ok;
  const ChunkedReads reads{cmd->config.seed, out.read_delay_ms};
  ok = produce(out.chunked, [&] { return write_chunked_capture(timeline, out.chunked, reads); }) &&
       ok;
  ok = produce(out.truth, [&] { return write_ground_truth(timeline, cmd->config, out.truth); }) &&
       ok;
  ok = produce(out.device,
               [&] { return pace_onto_device(timeline, out.device, cmd->config.baud); }) &&
       ok;
  return ok ? 0 : 1;
}
