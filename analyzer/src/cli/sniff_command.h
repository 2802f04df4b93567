// The `sniff` subcommand: live capture from RS485 taps or from a gateway's TCP traffic.
#pragma once

#include "cli/command_options.h"

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace pvtap::analyzer {

// SniffCommandLine: `pvtap sniff` as typed; parity is a word until run_sniff() reads it.
struct SniffCommandLine {
  SniffOptions options;
  std::string parity = "none";
  std::string baud = "9600";  // a rate, or "auto"
  std::string sample_rate;    // --samplerate as typed: 4000000, 4M, 500k
  // The line's settings as options, to tell whether they were given (--baud auto finds them).
  const CLI::Option* parity_option = nullptr;
  const CLI::Option* stop_bits_option = nullptr;
};

// Adds `sniff` to the program's command line; parsed values land in `command`.
CLI::App* add_sniff_command(CLI::App& app, SniffCommandLine& command);

// Runs a live capture after parsing; returns the exit status.
int run_sniff(SniffCommandLine& command);

// Runs a live capture with options already complete (extcap builds them itself); `options`
// must have live.devices or live.interface set. Returns the exit status.
int run_live_capture(SniffOptions& options);

}  // namespace pvtap::analyzer
