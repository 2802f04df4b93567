// Fuzz target command_line: `pvtap audit` and `pvtap sniff` option parsing (CLI11 with pvtap's
// options, validators and choices) and apply_choices() on arbitrary argument lists
// (NUL-separated in the input). A bad command line must end as a CLI11 parse error (the usage
// error of exit status 2), never as another exception or a crash.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "cli/audit_command.h"
#include "cli/common_options.h"
#include "cli/sniff_command.h"
#include "fuzz_input.h"

namespace {

// The arguments after the program name, in the reverse order CLI11's parse(vector&) wants.
std::vector<std::string> reversed_arguments(const std::uint8_t* data, std::size_t size) {
  std::vector<std::string> args = pvtap::fuzz::nul_separated_arguments(data, size);
  std::reverse(args.begin(), args.end());
  return args;
}

// The command line as pvtap builds it, made once: building CLI11's options and validators cost
// far more than parsing one argument list. Each input starts from the options as they were
// right after the commands were added (defaults written by CLI11 included; the options are
// bound by address, so they are reset in place), and CLI11 clears its own parse state when an
// app parses again: every input is parsed as a fresh `pvtap` would parse it. All but one list:
// CLI11's clear() keeps each app's parse_order(), which only grows, so the command line is built
// anew once those lists hold kMaxParseOrder options (3.4 million inputs grew them to 2 GiB).
struct CommandLine {
  static constexpr std::size_t kMaxParseOrder = 1 << 16;

  CLI::App app{"pvtap", "pvtap"};
  pvtap::analyzer::AuditOptions audit_options;
  pvtap::analyzer::SniffCommandLine sniff_command;
  CLI::App* audit = nullptr;
  CLI::App* sniff = nullptr;
  pvtap::analyzer::AuditOptions audit_defaults;
  pvtap::analyzer::SniffCommandLine sniff_defaults;

  CommandLine() {
    app.require_subcommand(1);
    audit = pvtap::analyzer::add_audit_command(app, audit_options);
    sniff = pvtap::analyzer::add_sniff_command(app, sniff_command);
    audit_defaults = audit_options;
    sniff_defaults = sniff_command;
  }

  bool worn() const {
    return app.parse_order().size() + audit->parse_order().size() + sniff->parse_order().size() >=
           kMaxParseOrder;
  }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace pvtap::analyzer;
  static auto command_line = std::make_unique<CommandLine>();
  if (command_line->worn()) command_line = std::make_unique<CommandLine>();
  command_line->audit_options = command_line->audit_defaults;
  command_line->sniff_command = command_line->sniff_defaults;
  auto args = reversed_arguments(data, size);
  try {
    command_line->app.parse(args);
  } catch (const CLI::ParseError&) {
    return 0;
  }
  if (command_line->audit->parsed()) apply_choices(command_line->audit_options);
  if (command_line->sniff->parsed()) apply_choices(command_line->sniff_command.options);
  return 0;
}
