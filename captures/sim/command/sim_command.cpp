#include "command/sim_command.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <iostream>

#include "devices/test_suite_server.h"
#include "dialects/inverter_dialect.h"

namespace pvtap::sim {
namespace {

// A dialect a simulated inverter speaks, by its name.
std::optional<Dialect> inverter_dialect_named(const std::string& name) {
  const std::optional<Dialect> d = dialect_named(name);
  if (!d || inverter_dialect(*d) == nullptr) return std::nullopt;
  return d;
}

// "gsl" or "gsl,hybrid,ascii" (a mixed bus; stations take the dialects in turn).
std::string parse_dialects(const std::string& text, std::vector<Dialect>& out) {
  out.clear();
  std::size_t from = 0;
  while (from <= text.size()) {
    const auto comma = std::min(text.find(',', from), text.size());
    const auto d = inverter_dialect_named(text.substr(from, comma - from));
    if (!d) return "unknown dialect in '" + text + "' (ascii, hybrid, gsl)";
    out.push_back(*d);
    from = comma + 1;
  }
  return {};
}

// Every device needs a station of its own, and a bus something on it.
std::string station_problem(const SimConfig& c, unsigned first_station) {
  const auto taken = [&](std::optional<std::uint8_t> s) {
    return s && *s >= first_station && *s < first_station + c.inverters;
  };
  if (c.inverters == 0 && !c.meter_station && !c.io_module_station && !c.test_server_station &&
      !c.battery_station && !c.sunspec_station)
    return "--inverters 0 needs a --meter, an --io-module, a --battery, a --sunspec or a "
           "--test-server";
  if (c.sunspec_station &&
      (taken(c.sunspec_station) || c.sunspec_station == c.meter_station ||
       c.sunspec_station == c.io_module_station || c.sunspec_station == c.battery_station ||
       c.sunspec_station == c.test_server_station))
    return "--sunspec needs a station of its own";
  if (taken(c.meter_station) || taken(c.io_module_station) || taken(c.test_server_station) ||
      taken(c.battery_station))
    return "--meter, --io-module, --battery and --test-server need stations no inverter has";
  if (c.meter_station && c.meter_station == c.io_module_station)
    return "--meter and --io-module need different stations";
  if (c.battery_station &&
      (c.battery_station == c.meter_station || c.battery_station == c.io_module_station ||
       c.battery_station == c.test_server_station))
    return "--battery needs a station of its own";
  if (c.address_conflict && !taken(c.address_conflict))
    return "--address-conflict needs the station of an inverter";
  if (c.masters > 1 && c.inverters == 0) return "--masters 2 needs inverters to poll";
  if (c.test_server_station) {
    // The test server's master also asks the station next to it, which must stay empty.
    const TestSuiteServer probe(*c.test_server_station);
    const std::uint8_t absent = probe.absent_station();
    if (c.test_server_station == c.meter_station || c.test_server_station == c.io_module_station ||
        absent == c.meter_station || absent == c.io_module_station || absent == c.battery_station ||
        taken(absent))
      return "--test-server needs its station and the next one to itself";
  }
  return {};
}

}  // namespace

std::optional<SimCommand> parse_sim_command(int argc, char** argv, int& exit_code) {
  SimCommand cmd;
  SimConfig& c = cmd.config;
  std::string dialects = "gsl", faults = "none", meter_order = "high_first";
  unsigned first_station = c.first_station;
  double start_s = static_cast<double>(c.start) / 1e6;
  CLI::App app{"pvtap-sim: a simulated RS485 bus of PV inverters, written as captures"};
  app.add_option("--seed", c.seed, "seed; one seed gives the same bytes every time");
  app.add_option("--dialect", dialects, "ascii, hybrid, gsl, or a list for a mixed bus");
  app.add_option("--inverters", c.inverters,
                 "number of inverters (0: only the --meter and --io-module devices)")
      ->check(CLI::Range(0, 31));
  app.add_option("--first-station", first_station, "address of the first inverter")
      ->check(CLI::Range(1, 200));
  app.add_option("--start", start_s, "simulated start time, Unix seconds (UTC = solar time)");
  app.add_option("--duration", c.duration_s, "seconds of bus traffic")->check(CLI::PositiveNumber);
  app.add_option("--period", c.period_s, "seconds between poll rounds")->check(CLI::PositiveNumber);
  app.add_option("--timeout", c.timeout_s, "seconds the master waits for a reply");
  app.add_option("--baud", c.baud, "bus speed")->check(CLI::Range(1200, 115200));
  app.add_option("--faults", faults,
                 "none, all, or kind=percent,... (corrupt missing slow "
                 "noise error_reply count_mismatch duplicate corrupt_request corrupt_data)");
  app.add_option("--meter", c.meter_station,
                 "station of a plain Modbus energy meter (SDM630 float registers, device "
                 "identification) polled after the inverters")
      ->check(CLI::Range(1, 247));
  app.add_option("--meter-word-order", meter_order,
                 "high_first (default) or low_first: which word of each float the meter sends "
                 "first")
      ->check(CLI::IsMember({"high_first", "low_first"}));
  app.add_option("--battery", c.battery_station,
                 "station of a plain Modbus home battery (signed, 32-bit, counter, flag and text "
                 "registers, no map) polled after the inverters")
      ->check(CLI::Range(1, 247));
  app.add_option("--sunspec", c.sunspec_station,
                 "station of a string inverter answering the SunSpec models (common, 103, 160 "
                 "with two MPPT modules) whose logger scans the model chain first")
      ->check(CLI::Range(1, 247));
  app.add_option("--io-module", c.io_module_station,
                 "station of a plain Modbus IO module (coils, discrete inputs, registers; "
                 "function codes 1 2 3 4 5 6 15 16) polled after the inverters")
      ->check(CLI::Range(1, 247));
  app.add_option("--test-server", c.test_server_station,
                 "station of a Modbus library's test suite server: report server ID, read/write "
                 "multiple registers (0x17), writes, a late reply for the station after it")
      ->check(CLI::Range(1, 247));
  app.add_option("--masters", c.masters,
                 "masters on the bus: 2 adds a second logger with a poll plan and period of its "
                 "own; where the two talk at once their frames collide")
      ->check(CLI::Range(1, 2));
  app.add_option("--second-period", c.second_period_s,
                 "--masters 2: seconds between the second master's rounds (--period x 1.37)")
      ->check(CLI::PositiveNumber);
  app.add_option("--address-conflict", c.address_conflict,
                 "a second device answering to this inverter's address, with other values, "
                 "after the first")
      ->check(CLI::Range(1, 247));
  app.add_flag("--echo", c.echo, "the tap's adapter echoes every request back to back");
  app.add_option("--pdu", cmd.outputs.pdu, "write a link type 252 capture");
  app.add_option("--gateway", cmd.outputs.gateway, "write an Ethernet/IPv4/TCP gateway capture");
  app.add_option("--chunked", cmd.outputs.chunked, "write a USER0 chunked serial capture");
  app.add_option("--read-delay", cmd.outputs.read_delay_ms,
                 "--chunked: the sniffer reads each USB transfer up to this many ms late")
      ->check(CLI::Range(0, 100));
  app.add_option("--duplex", cmd.outputs.duplex,
                 "a 4-wire (RS422) tap: write the requests' pair and the replies' pair as two "
                 "USER0 captures, each cut by its own USB adapter as --chunked is")
      ->expected(2)
      ->type_name("REQ REP");
  app.add_option("--truth", cmd.outputs.truth, "write the ground truth as JSON");
  app.add_option("--device", cmd.outputs.device, "play the bus onto a serial device or pty");
  app.add_option("--duplex-device", cmd.outputs.duplex_devices,
                 "a 4-wire bus played in real time: requests onto the first device, replies "
                 "(and noise) onto the second")
      ->expected(2)
      ->type_name("REQ REP");
  add_lan_options(app, cmd.outputs.lan);
  add_logic_options(app, cmd.outputs.logic);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    exit_code = app.exit(e) == 0 ? 0 : 2;
    return std::nullopt;
  }
  std::string error = parse_dialects(dialects, c.dialects);
  const auto plan = error.empty() ? parse_fault_plan(faults, error) : std::nullopt;
  if (!plan) {
    std::cerr << "pvtap-sim: " << error << "\n";
    exit_code = 2;
    return std::nullopt;
  }
  c.faults = *plan;
  c.meter_low_first = meter_order == "low_first";
  // A station field may hold fewer addresses than Modbus (ASCII's 0x00-0x1F).
  for (const Dialect d : c.dialects) {
    const unsigned last = inverter_dialect(d)->last_station;
    if (first_station + c.inverters - 1 > last) {
      std::cerr << "pvtap-sim: " << dialect_title(d) << " stations go up to " << last
                << "; lower --first-station or --inverters\n";
      exit_code = 2;
      return std::nullopt;
    }
  }
  error = station_problem(c, first_station);
  const SimOutputs& o = cmd.outputs;
  const bool bus_outputs = !o.pdu.empty() || !o.gateway.empty() || !o.chunked.empty() ||
                           !o.device.empty() || !o.logic.path.empty() || !o.duplex.empty() ||
                           !o.duplex_devices.empty();
  if (error.empty()) error = finish_lan_options(cmd.outputs.lan, c, bus_outputs);
  if (error.empty()) error = finish_logic_options(cmd.outputs.logic, c.baud);
  if (!error.empty()) {
    std::cerr << "pvtap-sim: " << error << "\n";
    exit_code = 2;
    return std::nullopt;
  }
  c.first_station = static_cast<std::uint8_t>(first_station);
  c.start = static_cast<Micros>(start_s * 1e6);
  return cmd;
}

}  // namespace pvtap::sim
