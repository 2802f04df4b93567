#include "cli/sniff_command.h"

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "cli/common_options.h"
#include "cli/exit_status.h"
#include "cli/mqtt_command_options.h"
#include "cli/sample_rate_argument.h"
#include "logic/input/logic_stream_source.h"
#include "pipeline/pipeline.h"
#include "run/run_output.h"
#include "sources/interface_source.h"
#include "sources/live_loop.h"
#include "sources/serial_taps.h"
#include "sources/stop_signal.h"

namespace pvtap::analyzer {
namespace {

const char* const kDescription =
    "Capture inverter bus traffic live and passively: from RS485 taps (serial adapters opened "
    "read-only, never written to) or from a serial-to-TCP gateway's traffic on a network "
    "interface. Frames, check verdicts, timeouts and noise are reported as they happen, in the "
    "same formats as `pvtap audit`; the report follows when the capture stops (Ctrl-C, "
    "SIGTERM, --duration or --count).";

const char* const kFooter =
    "\nSerial taps: the adapter must be set to the bus's baud rate, parity and stop bits, or\n"
    "--baud auto finds them from the traffic, never writing: it tries the standard rates\n"
    "(1200 to 115200) at 8N1, tells even from odd parity by which bytes fail, settles when a\n"
    "request and its reply both check (said on stderr, in the status line and the summary's\n"
    "serial), and searches again when the line stops giving frames that check.\n"
    "Pass adapters by their /dev/serial/by-id/ name: after an unplug pvtap reopens the same\n"
    "path (retrying with backoff) and reports the outage as a data-loss gap. On FTDI adapters\n"
    "the USB latency timer is lowered to 1 ms when it is writable, so that timestamps can\n"
    "judge the t1.5/t3.5 silences; the report says when they cannot.\n"
    "\nLogic analyzer: --logic - reads sigrok-cli's binary output on standard input, e.g.\n"
    "  sigrok-cli -d fx2lafw --config samplerate=4M --continuous -O binary |\n"
    "      pvtap sniff --logic - --samplerate 4M --channels D0,D1,D2\n"
    "--channels names the samples' bits from bit 0 on; the rate, format and idle level of\n"
    "every channel that talks are found from its first stretch, as pvtap audit does, and its\n"
    "characters are timed by the sample clock, so t1.5/t3.5 are judged.\n"
    "\nGateway traffic: --interface captures with libpcap (needs root or CAP_NET_RAW and\n"
    "CAP_NET_ADMIN); --port names the gateway's port(s), --filter adds a BPF filter.\n"
    "\nOutput on stdout as frames complete; --write FILE keeps a pcap (link type 252) for\n"
    "Wireshark, flushed record by record so an abrupt end loses nothing. --values FILE\n"
    "writes the register values as they arrive; --html FILE the report page when it stops.\n"
    "\nExit status: 0 stopped normally (also on SIGINT/SIGTERM); 1 findings (or no frame) with\n"
    "--fail-on errors, no frame with --fail-on empty; 2 usage error, a device or interface\n"
    "that cannot be opened.\n"
    "\nExamples:\n"
    "  pvtap sniff --device /dev/serial/by-id/usb-FTDI_FT232R_USB_UART_A10K1234-if00-port0\n"
    "  pvtap sniff --device /dev/ttyUSB0 --baud 19200 --parity even --format jsonl | jq .\n"
    "  pvtap sniff --device /dev/ttyUSB0 --device /dev/ttyUSB1 --write site.pcap\n"
    "  pvtap sniff --duplex --device /dev/ttyUSB0 --device /dev/ttyUSB1   (4-wire: requests'\n"
    "      pair on ttyUSB0, replies' pair on ttyUSB1)\n"
    "  pvtap sniff --device /dev/ttyUSB0 --baud auto\n"
    "  pvtap sniff --interface eth0 --port 4001 --duration 600 --summary-only\n"
    "  pvtap sniff --device /dev/ttyUSB0 --duration 3600 --html hour.html --values hour.csv\n"
    "  pvtap sniff --device /dev/ttyUSB0 --summary-only --mqtt mqtt://broker.lan\n"
    "      --mqtt-user pvtap --mqtt-password-file /etc/pvtap/mqtt.pw --mqtt-discovery\n"
    "\nIn Wireshark, once pvtap is installed (its Debian package, or `cmake --install`), the\n"
    "capture interfaces list \"RS485 tap\" for each serial port (pvtap answers Wireshark's\n"
    "extcap calls).\n";

void add_source_options(CLI::App& sniff, SniffCommandLine& c) {
  LiveOptions& live = c.options.live;
  sniff
      .add_option("--device", live.devices,
                  "serial device of an RS485 tap, opened read-only; repeat for several buses")
      ->type_name("PATH")
      ->allow_extra_args(false);
  sniff.add_flag("--duplex", live.duplex,
                 "a 4-wire (RS422) bus: the two --device taps are its two pairs, the first the "
                 "requests' (master to slaves), the second the replies'; one bus, both read-only");
  c.parity_option =
      sniff.add_option("--parity", c.parity, "parity of the bus's characters: none, even or odd")
          ->check(CLI::IsMember({"none", "even", "odd"}).description(""))
          ->type_name("PARITY")
          ->default_str("none");
  c.stop_bits_option =
      sniff.add_option("--stop-bits", live.line.stop_bits, "stop bits per character: 1 or 2")
          ->check(CLI::IsMember({1, 2}).description(""))
          ->type_name("N")
          ->default_str("1");
  sniff
      .add_option("--logic", live.logic_input,
                  "a logic analyzer's samples as sigrok-cli -O binary writes them (- for "
                  "standard input), with --samplerate and --channels")
      ->type_name("FILE");
  sniff
      .add_option("--samplerate", c.sample_rate, "--logic: samples per second (4000000, 4M, 500k)")
      ->type_name("RATE");
  sniff
      .add_option("--channels", live.logic_channels,
                  "--logic: the names of the samples' bits from bit 0 on (comma-separated), as "
                  "sigrok-cli --show lists the session's channels")
      ->type_name("NAMES")
      ->delimiter(',')
      ->allow_extra_args(false);
  sniff
      .add_option("--interface", live.interface,
                  "network interface to capture a serial-to-TCP gateway's traffic on")
      ->type_name("IFACE");
  sniff
      .add_option("--port", c.options.ports,
                  "gateway TCP/UDP port(s), comma-separated or repeated (with --interface)")
      ->check(CLI::Range(1, 65535).description(""))
      ->type_name("PORT")
      ->delimiter(',')
      ->allow_extra_args(false);
  sniff.add_option("--filter", live.filter, "BPF capture filter (with --interface)")
      ->type_name("BPF");
}

// --baud for sniff takes "auto" besides a rate: the tap then searches the bus's settings.
void add_baud_option(CLI::App& sniff, SniffCommandLine& c, BaudRange range) {
  sniff.remove_option(sniff.get_option("--baud"));
  const std::string help = "bus baud rate (" + std::to_string(range.min) + " to " +
                           std::to_string(range.max) +
                           "), or auto: serial taps search the rate, parity and stop bits "
                           "from the traffic, passively";
  sniff.add_option("--baud", c.baud, help)
      ->check(CLI::Validator(
          [range](std::string& value) {
            if (value == "auto") return std::string{};
            try {
              std::size_t used = 0;
              const unsigned long baud = std::stoul(value, &used);
              if (used == value.size() && baud >= range.min && baud <= range.max)
                return std::string{};
            } catch (const std::exception&) {
            }
            return value + " is neither auto nor a rate from " + std::to_string(range.min) +
                   " to " + std::to_string(range.max);
          },
          "", "baud"))
      ->type_name("BAUD")
      ->default_str("9600");
}

void add_stop_options(CLI::App& sniff, LiveOptions& live) {
  sniff.add_option("--duration", live.duration, "stop after this many seconds")
      ->check(CLI::PositiveNumber.description(""))
      ->type_name("SECONDS");
  sniff.add_option("--count", live.count, "stop after this many frames")
      ->check(CLI::PositiveNumber.description(""))
      ->type_name("N");
}

// A one-line reason why the sources given cannot be captured from; empty when they can.
std::string logic_problem(const LiveOptions& live) {
  if (!live.devices.empty() || !live.interface.empty()) {
    return "give one of --device, --interface and --logic";
  }
  if (live.search_line)
    return "--baud auto searches a serial tap's settings; it goes with --device";
  if (live.sample_rate <= 0) return "--logic needs --samplerate RATE (e.g. 4M)";
  if (live.logic_channels.empty()) return "--logic needs --channels NAMES (bit 0 first)";
  if (live.logic_channels.size() > 64) return "--logic reads at most 64 channels";
  return {};
}

std::string source_problem(const SniffOptions& o) {
  const LiveOptions& live = o.live;
  if (!live.logic_input.empty()) return logic_problem(live);
  if (live.sample_rate > 0 || !live.logic_channels.empty()) {
    return "--samplerate and --channels describe a --logic stream";
  }
  if (live.devices.empty() && live.interface.empty()) {
    return "sniff needs --device PATH, --interface IFACE or --logic - (see --help)";
  }
  if (!live.devices.empty() && !live.interface.empty()) {
    return "give either --device or --interface, not both";
  }
  if (!live.devices.empty() && (!o.ports.empty() || !live.filter.empty())) {
    return "--port and --filter select gateway traffic; they go with --interface";
  }
  if (live.search_line && live.devices.empty()) {
    return "--baud auto searches a serial tap's settings; it goes with --device";
  }
  if (live.duplex && live.devices.size() != 2) {
    return "--duplex reads two --device taps: the requests' pair, then the replies' pair";
  }
  if (live.duplex && live.search_line) {
    return "--duplex reads both pairs at one rate: give it with --baud";
  }
  return {};
}

// Opens the source the options name and captures from it until the loop says stop; false
// when the source could not be opened (the reason is on stderr, nothing ran).
template <typename Source>
bool capture_from(Source& source, const SniffOptions& o, Pipeline& pipeline, RunOutput& output,
                  LiveSources& live) {
  if (!source.open()) return false;
  LiveLoop loop(o.live, pipeline, output);
  source.run(loop, live);
  // Requests whose timeout ran out before the stop are timeouts, whether or not the loop woke
  // for them; the --write file carries that clock.
  pipeline.idle(loop.last_time());
  output.clock_ended(loop.last_time());
  pipeline.finish(loop.last_time());
  output.end_of_input(loop.last_time());
  return true;
}

int capture(const SniffOptions& o, const RegisterDecoder& decoder, OutputStream& out) {
  OutputSettings output_choice = output_settings(o);
  if (o.live.devices.size() == 1) output_choice.mqtt.lone_serial_bus = o.live.devices.front();
  if (o.live.duplex) output_choice.mqtt.lone_serial_bus = duplex_bus_name(o.live);
  // Each record reaches the --write file at once, so that an abrupt end loses nothing.
  output_choice.flush_each_record = true;
  output_choice.live = true;
  RunOutput output(output_choice, out);
  if (!output.open()) return kExitBadInput;
  PipelineSettings settings = pipeline_settings(o);
  // A logic stream is timed by its sample clock, from the stream's start.
  settings.from_recording_start = !o.live.logic_input.empty();
  Pipeline pipeline(settings, decoder, output.events());
  LiveSources live;
  bool opened = false;
  std::unique_ptr<LogicStreamSource> logic;
  if (!o.live.logic_input.empty()) {
    logic = std::make_unique<LogicStreamSource>(o.live, pipeline);
    opened = capture_from(*logic, o, pipeline, output, live);
  } else if (!o.live.devices.empty()) {
    SerialTaps taps(o.live, o.baud, pipeline);
    opened = capture_from(taps, o, pipeline, output, live);
  } else {
    InterfaceSource interface(o.live, o.ports, pipeline);
    opened = capture_from(interface, o, pipeline, output, live);
  }
  if (!opened) return kExitBadInput;
  AuditReport report = pipeline.report();
  report.written_records = output.written_records();
  report.live = live;
  SerialTaps::add_found_lines(report);
  if (logic) logic->add_found_lines(report);
  output.write_summary(report);
  out.flush();
  if (!output.close(report)) return kExitBadInput;
  return findings_status(o, report);
}

}  // namespace

CLI::App* add_sniff_command(CLI::App& app, SniffCommandLine& command) {
  CLI::App* sniff = app.add_subcommand("sniff", kDescription);
  sniff->footer(std::string(kFooter) + kMqttHelpFooter);
  add_source_options(*sniff, command);
  add_protocol_options(*sniff, command.options, kBaudRange);
  add_baud_option(*sniff, command, kBaudRange);
  add_stop_options(*sniff, command.options.live);
  add_output_options(*sniff, command.options);
  add_mqtt_options(*sniff, command.options.mqtt);
  return sniff;
}

int run_sniff(SniffCommandLine& command) {
  SniffOptions& o = command.options;
  if (command.baud == "auto") {
    for (const CLI::Option* given : {command.parity_option, command.stop_bits_option}) {
      if (given != nullptr && given->count() > 0) {
        std::fprintf(stderr,
                     "pvtap: --baud auto finds the parity and stop bits itself: leave out %s\n",
                     given->get_name().c_str());
        return kExitBadInput;
      }
    }
  }
  o.live.line.parity = SerialLine::parity_letter(command.parity);
  o.live.search_line = command.baud == "auto";
  if (!o.live.search_line) o.baud = static_cast<std::uint32_t>(std::stoul(command.baud));
  if (!read_sample_rate_option(command.sample_rate, o.live.sample_rate)) return kExitBadInput;
  o.live.status_line = ::isatty(STDERR_FILENO) == 1 && o.format_name == "text";
  return run_live_capture(o);
}

int run_live_capture(SniffOptions& o) {
  apply_choices(o);
  if (const std::string problem = source_problem(o); !problem.empty()) {
    std::fprintf(stderr, "pvtap: %s\n", problem.c_str());
    return kExitBadInput;
  }
  RegisterDecoder decoder(DecoderOptions{o.gsl_ids, PairRule::Binary, !o.no_sunspec});
  if (!load_maps(o, decoder)) return kExitBadInput;
  install_stop_handlers();
  std::FILE* sink = o.live.quiet ? std::fopen("/dev/null", "w") : stdout;
  int status = kExitBadInput;
  {
    OutputStream out(sink);
    status = capture(o, decoder, out);
    out.flush();
    if (out.failed()) {
      std::fprintf(stderr, "pvtap: cannot write the output\n");
      status = kExitBadInput;
    }
  }
  if (sink != stdout) std::fclose(sink);
  return status;
}

}  // namespace pvtap::analyzer
