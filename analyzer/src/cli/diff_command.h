// The `diff` subcommand: two audits of the same buses, before and after a change, compared.
#pragma once

#include <string>

#include "cli/command_options.h"
#include "diff/capture_diff.h"

namespace CLI {
class App;
}  // namespace CLI

namespace pvtap::analyzer {

struct DiffCommandLine {
  AuditOptions reading;  // how both sides are read (protocol and input options)
  std::string before;    // a side: a file, or several comma-separated
  std::string after;
  bool raw = false;             // both sides are plain dumps of bus bytes
  std::string format = "text";  // text or jsonl
  std::string html_path;
  DiffThresholds thresholds;
};

// Adds `diff` to the program's command line; parsed values land in `command`.
CLI::App* add_diff_command(CLI::App& app, DiffCommandLine& command);

// Audits both sides and writes their differences. Returns the exit status: 0 none beyond the
// noise of sampling, 1 some, 2 an error (as diff(1)).
int run_diff(DiffCommandLine& command);

}  // namespace pvtap::analyzer
