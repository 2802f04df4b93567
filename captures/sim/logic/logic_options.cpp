#include "logic/logic_options.h"

#include <sstream>

namespace pvtap::sim {
namespace {

// "8N1", "8E1", "8O1", "8N2".
bool parse_format(const std::string& text, UartFormat& out) {
  if (text.size() != 3 || text[0] != '8' || (text[2] != '1' && text[2] != '2')) return false;
  const char p = text[1];
  if (p != 'N' && p != 'E' && p != 'O') return false;
  out.data_bits = 8;
  out.parity = p == 'N' ? Parity::None : p == 'E' ? Parity::Even : Parity::Odd;
  out.stop_bits = static_cast<unsigned>(text[2] - '0');
  return true;
}

std::string parse_channels(LogicOptions& o) {
  o.bus = o.tx = o.rx = o.de = false;
  std::istringstream in(o.channels_text);
  for (std::string name; std::getline(in, name, ',');) {
    bool& flag = name == "bus" ? o.bus : name == "tx" ? o.tx : name == "rx" ? o.rx : o.de;
    if (name != "bus" && name != "tx" && name != "rx" && name != "de")
      return "--sr-channels: unknown channel '" + name + "' (bus, tx, rx, de)";
    flag = true;
  }
  if (!o.bus && !o.tx && !o.rx) return "--sr-channels needs bus, tx or rx";
  return {};
}

}  // namespace

void add_logic_options(CLI::App& app, LogicOptions& logic) {
  auto* sr = app.add_option(
      "--sr", logic.path, "write the bus as a sigrok session (srzip) sampled by a logic analyzer");
  app.add_option("--samplerate", logic.sample_rate, "--sr: samples per second")
      ->check(CLI::Range(1e3, 1e9))
      ->needs(sr);
  app.add_option("--format", logic.format_text, "--sr: character format (8N1 8E1 8O1 8N2)")
      ->needs(sr);
  app.add_option("--clock-deviation", logic.clock_deviation_pct,
                 "--sr: percent the talkers' bit clock is slow (+) or fast (-)")
      ->check(CLI::Range(-10.0, 10.0))
      ->needs(sr);
  app.add_option("--jitter", logic.jitter_pct,
                 "--sr: each edge moved by up to this percent of a bit")
      ->check(CLI::Range(0.0, 25.0))
      ->needs(sr);
  app.add_flag("--inverted", logic.format.inverted, "--sr: UART channels idle low")->needs(sr);
  app.add_option("--sr-channels", logic.channels_text,
                 "--sr: bus (A-B), tx and rx (the master's UART), de (driver enable per talker)")
      ->needs(sr);
  app.add_option("--glitches", logic.glitch_pct,
                 "--sr: percent of driver switchings that put a glitch byte on the bus")
      ->check(CLI::Range(0, 100))
      ->needs(sr);
  app.add_option("--violations", logic.violations,
                 "--sr: replies 2.5 characters after their request, and requests with a pause of "
                 "2 characters inside")
      ->needs(sr);
  app.add_flag("--truncate-last-byte", logic.truncate_last_byte,
               "--sr: the first inverter releases its driver before its last stop bit ends")
      ->needs(sr);
  app.add_option("--undriven", logic.undriven,
                 "--sr: what the A-B line reads where no driver drives it: mark (failsafe bias) "
                 "or space (none: it falls at every release, a short pulse at every switch-on)")
      ->check(CLI::IsMember({"mark", "space"}))
      ->needs(sr);
}

std::string finish_logic_options(LogicOptions& logic, unsigned baud) {
  if (logic.path.empty()) return {};
  const bool inverted = logic.format.inverted;
  if (!parse_format(logic.format_text, logic.format))
    return "--format: '" + logic.format_text + "' is not one of 8N1 8E1 8O1 8N2";
  logic.format.inverted = inverted;
  logic.undriven_space = logic.undriven == "space";
  if (logic.sample_rate < 8.0 * baud)
    return "--samplerate: under 8 samples per bit at --baud " + std::to_string(baud);
  return parse_channels(logic);
}

}  // namespace pvtap::sim
