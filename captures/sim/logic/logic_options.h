// The command line of --sr: how the simulated line is sampled and what the session holds.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "pvtap/uart/uart_format.h"

namespace pvtap::sim {

// LogicOptions: the logic session a run writes (path empty: none).
struct LogicOptions {
  std::string path;
  double sample_rate = 1e6;
  std::string format_text = "8N1";
  UartFormat format;                  // read from format_text by finish_logic_options
  double clock_deviation_pct = 0.0;   // every talker's bit clock this much slow (+) or fast (-)
  double jitter_pct = 0.0;            // each edge moved at random by up to this share of a bit
  std::string channels_text = "bus";  // bus, tx, rx, de
  bool bus = true, tx = false, rx = false, de = false;
  unsigned glitch_pct = 0;          // chance that a driver switching puts a glitch byte on the bus
  unsigned violations = 0;          // early replies, and as many requests with a pause inside
  bool truncate_last_byte = false;  // the first station releases its driver mid stop bit
  // What the A-B line reads where no driver drives it: "mark" (failsafe bias holds it idle)
  // or "space" (no bias: it falls at every release and only a driver lifts it).
  std::string undriven = "mark";
  bool undriven_space = false;  // read from `undriven` by finish_logic_options
};

void add_logic_options(CLI::App& app, LogicOptions& logic);

// After parsing: the format and channels read; an error text when they make no session.
std::string finish_logic_options(LogicOptions& logic, unsigned baud);

}  // namespace pvtap::sim
